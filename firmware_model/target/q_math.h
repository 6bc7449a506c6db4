// Saturating, rounding and sign-extension primitives of the dsPIC30F/33F DSP engine, the only
// integer arithmetic the engine model (dsp_engine.h) builds on. Target code: fixed-width integers,
// explicit overflow policy per function (physics.md section 5.2; STYLE.md 8.7 items 32-33).
// Conventions: accumulator values are 40-bit two's complement held sign-extended in int64_t
// ("9.31": 8 guard bits + 1.31); Q15 is int16_t (1.15), Q31 is int32_t (1.31).
// Right shifts of negative values are arithmetic (C++20 defines >> so).
#pragma once

#include <cstdint>

namespace adahrs::firmware_model {

inline constexpr int64_t kAcc40Max = (INT64_C(1) << 39) - 1;  ///< 0x7F_FFFF_FFFF
inline constexpr int64_t kAcc40Min = -(INT64_C(1) << 39);     ///< 0x80_0000_0000
inline constexpr int64_t kAcc31Max = (INT64_C(1) << 31) - 1;  ///< 0x00_7FFF_FFFF
inline constexpr int64_t kAcc31Min = -(INT64_C(1) << 31);     ///< 0xFF_8000_0000
inline constexpr int16_t kQ15Max = INT16_MAX;                 ///< 0x7FFF = 0.999969482
inline constexpr int16_t kQ15Min = INT16_MIN;                 ///< 0x8000 = -1.0

/// Wraps any int64 to 40 bits and sign-extends (what the 40-bit adder does without saturation).
constexpr int64_t SignExtend40(int64_t v) {
  const uint64_t low40 = static_cast<uint64_t>(v) & ((UINT64_C(1) << 40) - 1);
  const uint64_t sign = UINT64_C(1) << 39;
  return static_cast<int64_t>(low40 ^ sign) - static_cast<int64_t>(sign);
}

/// Clamps to [lo, hi]; `*clipped` is set true if it had to (never cleared).
constexpr int64_t Clamp64(int64_t v, int64_t lo, int64_t hi, bool* clipped) {
  if (v > hi) {
    *clipped = true;
    return hi;
  }
  if (v < lo) {
    *clipped = true;
    return lo;
  }
  return v;
}

/// Saturates a value (any width) to Q15 / int16 (the SATDW rule, sign from the wide value).
constexpr int16_t SatQ15(int64_t v) {
  return static_cast<int16_t>(v > kQ15Max ? kQ15Max : (v < kQ15Min ? kQ15Min : v));
}

/// Saturates to Q31 / int32.
constexpr int32_t SatQ31(int64_t v) {
  return static_cast<int32_t>(v > kAcc31Max ? kAcc31Max : (v < kAcc31Min ? kAcc31Min : v));
}

/// Exact arithmetic shift: positive = right (toward minus infinity), negative = left. |shift| < 48.
constexpr int64_t ShiftArith(int64_t v, int32_t shift) {
  return shift >= 0 ? (v >> shift) : static_cast<int64_t>(static_cast<uint64_t>(v) << -shift);
}

/// The dsPIC rounding increment for taking bits 31..16 of a 40-bit value (SAC.R, MAC write-back):
/// conventional rounds up when the low word >= 0x8000; convergent rounds a tie (low word exactly
/// 0x8000) up only when bit 16 is 1, i.e. ties to even.
constexpr int64_t RoundHighWord(int64_t acc40, bool convergent) {
  const int64_t low = acc40 & 0xFFFF;
  const int64_t high = acc40 >> 16;
  if (low > 0x8000) return high + 1;
  if (low < 0x8000) return high;
  return convergent ? high + (high & 1) : high + 1;
}

/// High and low words of a 32-bit value as the W-register pair holds them.
constexpr int16_t HighWord(int32_t v) {
  return static_cast<int16_t>(static_cast<uint32_t>(v) >> 16);
}
constexpr uint16_t LowWord(int32_t v) {
  return static_cast<uint16_t>(static_cast<uint32_t>(v) & 0xFFFFu);
}
/// Joins a W-register pair into a 32-bit value.
constexpr int32_t JoinWords(int16_t high, uint16_t low) {
  return static_cast<int32_t>((static_cast<uint32_t>(static_cast<uint16_t>(high)) << 16) | low);
}

}  // namespace adahrs::firmware_model
