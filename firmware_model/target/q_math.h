// Saturating, rounding, shifting and sign-extension primitives of the dsPIC30F/33F DSP engine, the
// only integer arithmetic the engine model (dsp_engine.h) builds on. Target code, C99: fixed-width
// integers, explicit overflow policy per function (physics.md section 5.2; STYLE.md 8.7 items
// 32-33), correct where int is 16 bits (every operand is widened by an explicit cast before an
// operation whose result could leave 16 bits).
// Conventions: accumulator values are 40-bit two's complement held sign-extended in int64_t
// ("9.31": 8 guard bits + 1.31); Q15 is int16_t (1.15), Q31 is int32_t (1.31).
// Implementation-defined behaviour is kept out of every other file by three rules kept here:
//   - the one arithmetic right shift of a signed value is fw_asr64 (floor division by a power of
//     two, written so that it never shifts a signed value: C99 6.5.7p5 leaves that to the
//     compiler);
//   - left shifts of signed values go through uint64_t (fw_shift_arith);
//   - an unsigned bit pattern becomes a signed value only through fw_s16/s32/s64_from_bits (C99
//     6.3.1.3p3 leaves an out-of-range conversion to the compiler).
#ifndef ADAHRS_FW_Q_MATH_H
#define ADAHRS_FW_Q_MATH_H

#include <stdbool.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define FW_ACC40_MAX (INT64_C(0x7FFFFFFFFF))       ///< 2^39 - 1
#define FW_ACC40_MIN (-INT64_C(0x7FFFFFFFFF) - 1)  ///< -2^39
#define FW_ACC31_MAX (INT64_C(0x7FFFFFFF))         ///< 2^31 - 1
#define FW_ACC31_MIN (-INT64_C(0x7FFFFFFF) - 1)    ///< -2^31
#define FW_Q15_MAX ((int16_t)INT16_MAX)            ///< 0x7FFF = 0.999969482
#define FW_Q15_MIN ((int16_t)INT16_MIN)            ///< 0x8000 = -1.0

/// The int16 whose two's-complement bit pattern is `bits`.
static inline int16_t fw_s16_from_bits(uint16_t bits) {
  int16_t value = 0;
  if (bits <= (uint16_t)INT16_MAX) {
    value = (int16_t)bits;
  } else {
    const uint16_t below_wrap = (uint16_t)(0xFFFFu - bits);  // 65535 - bits, 0..32767
    value = (int16_t)(-(int16_t)below_wrap - 1);
  }
  return value;
}

/// The int32 whose two's-complement bit pattern is `bits`.
static inline int32_t fw_s32_from_bits(uint32_t bits) {
  int32_t value = 0;
  if (bits <= (uint32_t)INT32_MAX) {
    value = (int32_t)bits;
  } else {
    const uint32_t below_wrap = UINT32_MAX - bits;  // 0..2^31 - 1
    value = -(int32_t)below_wrap - 1;
  }
  return value;
}

/// The int64 whose two's-complement bit pattern is `bits`.
static inline int64_t fw_s64_from_bits(uint64_t bits) {
  int64_t value = 0;
  if (bits <= (uint64_t)INT64_MAX) {
    value = (int64_t)bits;
  } else {
    const uint64_t below_wrap = UINT64_MAX - bits;  // 0..2^63 - 1
    value = -(int64_t)below_wrap - 1;
  }
  return value;
}

/// Arithmetic right shift: floor(v / 2^shift), shift 0..63. Toward minus infinity for every v, as
/// the dsPIC's ASR and SFTAC do. Only the bit pattern is shifted, logically: a negative v is
/// complemented first (~v is v's magnitude minus one) and the result complemented back, without
/// a branch.
static inline int64_t fw_asr64(int64_t v, uint8_t shift) {
  const uint64_t bits = (uint64_t)v;
  const uint64_t sign_fill = (uint64_t)0u - (bits >> 63);  // all ones for a negative v
  return fw_s64_from_bits(((bits ^ sign_fill) >> shift) ^ sign_fill);
}

/// Wraps any int64 to 40 bits and sign-extends (what the 40-bit adder does without saturation).
static inline int64_t fw_sign_extend40(int64_t v) {
  const uint64_t low40 = (uint64_t)v & ((UINT64_C(1) << 40) - 1u);
  const uint64_t sign = UINT64_C(1) << 39;
  const uint64_t biased = low40 ^ sign;  // v + 2^39 modulo 2^40
  return (int64_t)biased - (int64_t)sign;
}

/// Clamps to [lo, hi]; `*clipped` is set true if it had to (never cleared).
static inline int64_t fw_clamp64(int64_t v, int64_t lo, int64_t hi, bool* clipped) {
  int64_t result = v;
  if (v > hi) {
    *clipped = true;
    result = hi;
  } else if (v < lo) {
    *clipped = true;
    result = lo;
  } else {
    // in range
  }
  return result;
}

/// Saturates a value (any width) to Q15 / int16 (the SATDW rule, sign from the wide value).
static inline int16_t fw_sat_q15(int64_t v) {
  return (v > (int64_t)FW_Q15_MAX) ? FW_Q15_MAX
                                   : ((v < (int64_t)FW_Q15_MIN) ? FW_Q15_MIN : (int16_t)v);
}

/// Saturates to Q31 / int32.
static inline int32_t fw_sat_q31(int64_t v) {
  return (v > FW_ACC31_MAX) ? INT32_MAX : ((v < FW_ACC31_MIN) ? INT32_MIN : (int32_t)v);
}

/// Exact arithmetic shift: positive = right (toward minus infinity), negative = left (modulo
/// 2^64, as a barrel shifter would). |shift| < 48.
static inline int64_t fw_shift_arith(int64_t v, int8_t shift) {
  return (shift >= 0) ? fw_asr64(v, (uint8_t)shift)
                      : fw_s64_from_bits((uint64_t)v << (uint8_t)(-(int16_t)shift));
}

/// The dsPIC rounding increment for taking bits 31..16 of a 40-bit value (SAC.R, MAC write-back):
/// conventional rounds up when the low word >= 0x8000; convergent rounds a tie (low word exactly
/// 0x8000) up only when bit 16 is 1, i.e. ties to even.
static inline int64_t fw_round_high_word(int64_t acc40, bool convergent) {
  const uint64_t low = (uint64_t)acc40 & UINT64_C(0xFFFF);
  const int64_t high = fw_asr64(acc40, 16u);
  int64_t rounded = high + 1;
  if (low < UINT64_C(0x8000)) {
    rounded = high;
  } else if ((low == UINT64_C(0x8000)) && convergent) {
    const uint64_t odd = (uint64_t)high & 1u;
    rounded = high + (int64_t)odd;
  } else {
    // above the tie, or a conventional tie: up
  }
  return rounded;
}

/// High and low words of a 32-bit value as the W-register pair holds them.
static inline int16_t fw_high_word(int32_t v) {
  return fw_s16_from_bits((uint16_t)((uint32_t)v >> 16));
}
static inline uint16_t fw_low_word(int32_t v) { return (uint16_t)((uint32_t)v & UINT32_C(0xFFFF)); }
/// Joins a W-register pair into a 32-bit value.
static inline int32_t fw_join_words(int16_t high, uint16_t low) {
  return fw_s32_from_bits(((uint32_t)(uint16_t)high << 16) | (uint32_t)low);
}

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_Q_MATH_H
