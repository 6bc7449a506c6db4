// Bit-exact model of the dsPIC30F/33F DSP engine and the few MCU instructions the compensator
// needs, with an instruction and cycle counter (physics.md sections 5.1-5.2). One function per
// instruction, so the compensator reads as the instruction sequence it is; on the dsPIC each maps
// to one instruction (XC16's DSP builtins __builtin_mpy, __builtin_mac, __builtin_sac, ...) or runs
// as it stands, a C emulation with the same results. Modelled: the two 40-bit accumulators, the
// 17x17 multiplier (fractional or integer, signed or unsigned), MAC-class and accumulator
// instructions, MUL.xx, DIVF / DIV.SD / DIV.UD, saturation modes (SATA/SATB, ACCSAT, SATDW), the
// SA/SB/OA/OB flags and rounding (RND). Cycle costs (DS70157): 1 per instruction except DIVx (19
// incl. REPEAT), a taken branch (2), CALL (2) and RETURN (3).
// Units: 16-bit words, 40-bit accumulators (int64, sign-extended); cycles.
// The instruction list, assumptions (R) and what is left out: docs/firmware-compensator.md ("What
// the model covers", after "Dropping target/ into an MPLAB X project").
// Not modelled: the X/Y prefetch AGUs and W13 write-back, the pipeline, interrupts, DO/REPEAT
// hardware beyond their cycle charge, OA/OB traps.
#ifndef ADAHRS_FW_DSP_ENGINE_H
#define ADAHRS_FW_DSP_ENGINE_H

#include <stdbool.h>
#include <stdint.h>

#include "q_math.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { FW_ACC_A = 0, FW_ACC_B = 1 } FwAcc;

/// The other accumulator.
static inline FwAcc fw_other_acc(FwAcc acc) { return (acc == FW_ACC_A) ? FW_ACC_B : FW_ACC_A; }

/// Instruction classes counted by the engine (one entry of the cycle table each).
typedef enum {
  FW_OP_MPY,
  FW_OP_MAC,
  FW_OP_MSC,
  FW_OP_LAC,
  FW_OP_SAC,
  FW_OP_SAC_R,
  FW_OP_SFTAC,
  FW_OP_ADD_ACC,
  FW_OP_SUB_ACC,
  FW_OP_NEG_ACC,
  FW_OP_ADD_WORD_ACC,
  FW_OP_CLR_ACC,
  FW_OP_MOV_ACC_WORD,
  FW_OP_MUL_SS,
  FW_OP_MUL_SU,
  FW_OP_MUL_UU,
  FW_OP_DIV_F,
  FW_OP_DIV_SD,
  FW_OP_DIV_UD,
  FW_OP_MOV,
  FW_OP_ALU,
  FW_OP_BRANCH,
  FW_OP_CALL,
  FW_OP_RETURN,
  FW_OP_COUNT
} FwDspOp;

/// Documented cycle cost of one instruction of class `op` (physics.md 5.1: MAC-class, LAC/SAC,
/// SFTAC, MOV, MUL are single cycle; DIVx 19 with REPEAT #17; a taken branch, CALL 2; RETURN 3).
/// Inline, so that a charge of a known instruction compiles to a constant.
static inline uint8_t fw_dsp_op_cycles(FwDspOp op) {
  uint8_t cycles = 1u;
  if ((op == FW_OP_DIV_F) || (op == FW_OP_DIV_SD) || (op == FW_OP_DIV_UD)) {
    cycles = 19u;
  } else if ((op == FW_OP_BRANCH) || (op == FW_OP_CALL)) {
    cycles = 2u;
  } else if (op == FW_OP_RETURN) {
    cycles = 3u;
  } else {
    // single cycle
  }
  return cycles;
}
/// Mnemonic of `op` for cycle tables.
const char* fw_dsp_op_name(FwDspOp op);

/// CORCON bits that the arithmetic depends on.
typedef struct {
  bool integer_mode;         ///< IF: 1 = integer, 0 = fractional (product << 1)
  bool unsigned_mode;        ///< US: operands of MPY/MAC unsigned
  bool saturate_a;           ///< SATA
  bool saturate_b;           ///< SATB
  bool super_saturation;     ///< ACCSAT: 1 = bit-39 (9.31), 0 = bit-31 (1.31)
  bool saturate_writes;      ///< SATDW
  bool convergent_rounding;  ///< RND: 0 = convergent (reset default), 1 = conventional
} FwDspConfig;

/// Fractional, signed, SATA, SATB, 1.31 saturation, SATDW, convergent rounding.
FwDspConfig fw_dsp_config_default(void);

typedef struct {
  int32_t quotient;
  int32_t remainder;
} FwDivResult;

/// The engine's state and its counters.
typedef struct {
  FwDspConfig config;
  int64_t acc[2];  ///< indexed by FwAcc
  bool sa;         ///< sticky saturation of A
  bool sb;         ///< sticky saturation of B
  bool math_error;
  uint32_t cycles;
  uint32_t instructions;
  uint32_t op_counts[FW_OP_COUNT];
} FwDspEngine;

/// Accumulators cleared, flags and counters zero, configuration `config`.
void fw_dsp_init(FwDspEngine* engine, FwDspConfig config);
void fw_dsp_reset_counters(FwDspEngine* engine);
/// Reads and clears SA/SB (a BTSC on SR plus a BCLR: charged 2 cycles).
bool fw_dsp_test_and_clear_saturation(FwDspEngine* engine);
/// OA / OB: the accumulator holds a value beyond 1.31.
bool fw_dsp_overflowed31(const FwDspEngine* engine, FwAcc acc);

// ---- MCU divide (19 cycles each).
/// DIVF: fractional num/den, needs |num| < |den|; quotient Q15, remainder.
FwDivResult fw_dsp_div_f(FwDspEngine* engine, int16_t num, int16_t den);
/// DIV.SD: signed 32/16, quotient must fit int16.
FwDivResult fw_dsp_div_sd(FwDspEngine* engine, int32_t num, int16_t den);
/// DIV.UD: unsigned 32/16, quotient must fit uint16.
FwDivResult fw_dsp_div_ud(FwDspEngine* engine, uint32_t num, uint16_t den);

// The single-instruction operations are defined here so that the compensator's instruction
// sequences compile to straight-line arithmetic (a call per instruction was most of the rig's
// time on the host).

static inline void fw_dsp_charge(FwDspEngine* engine, FwDspOp op, uint8_t count) {
  engine->op_counts[op] += count;
  engine->instructions += count;
  engine->cycles += (uint32_t)count * (uint32_t)fw_dsp_op_cycles(op);
}

// ---- Charges for plain MCU instructions whose result the caller computes itself.
static inline void fw_dsp_charge_mov(FwDspEngine* engine, uint8_t count) {
  fw_dsp_charge(engine, FW_OP_MOV, count);
}
static inline void fw_dsp_charge_alu(FwDspEngine* engine, uint8_t count) {
  fw_dsp_charge(engine, FW_OP_ALU, count);
}
static inline void fw_dsp_charge_branch(FwDspEngine* engine, uint8_t count) {
  fw_dsp_charge(engine, FW_OP_BRANCH, count);
}
/// CALL + RETURN of one subroutine.
static inline void fw_dsp_charge_call_return(FwDspEngine* engine) {
  fw_dsp_charge(engine, FW_OP_CALL, 1u);
  fw_dsp_charge(engine, FW_OP_RETURN, 1u);
}

/// The 17x17 multiplier: operands sign- or zero-extended into bit 17, 33-bit product, doubled in
/// fractional mode.
static inline int64_t fw_dsp_product(const FwDspEngine* engine, int16_t a, int16_t b) {
  const int64_t ea = engine->config.unsigned_mode ? (int64_t)(uint16_t)a : (int64_t)a;
  const int64_t eb = engine->config.unsigned_mode ? (int64_t)(uint16_t)b : (int64_t)b;
  const int64_t p = ea * eb;
  return engine->config.integer_mode ? p : (p * 2);
}

/// Applies the saturation mode of `acc` to an exact result and stores it.
static inline void fw_dsp_write(FwDspEngine* engine, FwAcc acc, int64_t exact) {
  const bool saturate = (acc == FW_ACC_A) ? engine->config.saturate_a : engine->config.saturate_b;
  bool overflowed = false;
  int64_t value = 0;
  if (saturate) {
    value = engine->config.super_saturation
                ? fw_clamp64(exact, FW_ACC40_MIN, FW_ACC40_MAX, &overflowed)
                : fw_clamp64(exact, FW_ACC31_MIN, FW_ACC31_MAX, &overflowed);
  } else {
    value = fw_sign_extend40(exact);
    overflowed = (value != exact);  // catastrophic overflow past bit 39
  }
  if (overflowed) {
    if (acc == FW_ACC_A) {
      engine->sa = true;
    } else {
      engine->sb = true;
    }
  }
  engine->acc[acc] = value;
}

// ---- DSP instructions (1 cycle each). Shifts: positive = right, negative = left.
/// MPY a*b -> acc.
static inline void fw_dsp_mpy(FwDspEngine* engine, FwAcc acc, int16_t a, int16_t b) {
  fw_dsp_charge(engine, FW_OP_MPY, 1u);
  fw_dsp_write(engine, acc, fw_dsp_product(engine, a, b));
}

/// MAC acc += a*b.
static inline void fw_dsp_mac(FwDspEngine* engine, FwAcc acc, int16_t a, int16_t b) {
  fw_dsp_charge(engine, FW_OP_MAC, 1u);
  fw_dsp_write(engine, acc, engine->acc[acc] + fw_dsp_product(engine, a, b));
}

/// MSC acc -= a*b.
static inline void fw_dsp_msc(FwDspEngine* engine, FwAcc acc, int16_t a, int16_t b) {
  fw_dsp_charge(engine, FW_OP_MSC, 1u);
  fw_dsp_write(engine, acc, engine->acc[acc] - fw_dsp_product(engine, a, b));
}

/// LAC: word into bits 31..16, sign-extended, low word cleared, then shifted by -8..+7.
static inline void fw_dsp_lac(FwDspEngine* engine, FwAcc acc, int16_t word, int8_t shift) {
  fw_dsp_charge(engine, FW_OP_LAC, 1u);
  fw_dsp_write(engine, acc, fw_shift_arith((int64_t)word * INT64_C(65536), shift));
}

/// Bits 31..16 of the accumulator shifted by -8..+7 (the barrel shifter's 40-bit output),
/// truncated or rounded per RND, saturated per SATDW or wrapped to 16 bits.
static inline int16_t fw_dsp_store(const FwDspEngine* engine, FwAcc acc, int8_t shift, bool round) {
  const int64_t shifted = fw_sign_extend40(fw_shift_arith(engine->acc[acc], shift));
  const int64_t high = round ? fw_round_high_word(shifted, engine->config.convergent_rounding)
                             : fw_asr64(shifted, 16u);
  return engine->config.saturate_writes
             ? fw_sat_q15(high)
             : fw_s16_from_bits((uint16_t)((uint64_t)high & UINT64_C(0xFFFF)));
}

/// SAC: stores bits 31..16 of (acc shifted by -8..+7), truncated, with SATDW.
static inline int16_t fw_dsp_sac(FwDspEngine* engine, FwAcc acc, int8_t shift) {
  fw_dsp_charge(engine, FW_OP_SAC, 1u);
  return fw_dsp_store(engine, acc, shift, false);
}

/// SAC.R: as SAC but rounded per RND.
static inline int16_t fw_dsp_sac_r(FwDspEngine* engine, FwAcc acc, int8_t shift) {
  fw_dsp_charge(engine, FW_OP_SAC_R, 1u);
  return fw_dsp_store(engine, acc, shift, true);
}

/// SFTAC by -16..16.
static inline void fw_dsp_sftac(FwDspEngine* engine, FwAcc acc, int8_t shift) {
  fw_dsp_charge(engine, FW_OP_SFTAC, 1u);
  fw_dsp_write(engine, acc, fw_shift_arith(engine->acc[acc], shift));
}

/// ADD Acc: dst += other.
static inline void fw_dsp_add_acc(FwDspEngine* engine, FwAcc dst) {
  fw_dsp_charge(engine, FW_OP_ADD_ACC, 1u);
  fw_dsp_write(engine, dst, engine->acc[dst] + engine->acc[fw_other_acc(dst)]);
}

/// SUB Acc: dst -= other.
static inline void fw_dsp_sub_acc(FwDspEngine* engine, FwAcc dst) {
  fw_dsp_charge(engine, FW_OP_SUB_ACC, 1u);
  fw_dsp_write(engine, dst, engine->acc[dst] - engine->acc[fw_other_acc(dst)]);
}

/// NEG Acc.
static inline void fw_dsp_neg_acc(FwDspEngine* engine, FwAcc acc) {
  fw_dsp_charge(engine, FW_OP_NEG_ACC, 1u);
  fw_dsp_write(engine, acc, -engine->acc[acc]);
}

/// ADD Ws,#shift,Acc: word aligned like LAC, added to acc.
static inline void fw_dsp_add_word_acc(FwDspEngine* engine, FwAcc acc, int16_t word, int8_t shift) {
  fw_dsp_charge(engine, FW_OP_ADD_WORD_ACC, 1u);
  fw_dsp_write(
      engine, acc, engine->acc[acc] + fw_shift_arith((int64_t)word * INT64_C(65536), shift));
}

/// CLR Acc.
static inline void fw_dsp_clr_acc(FwDspEngine* engine, FwAcc acc) {
  fw_dsp_charge(engine, FW_OP_CLR_ACC, 1u);
  engine->acc[acc] = 0;
}

// ---- MOV to/from the memory-mapped accumulator words (1 cycle each, no saturation).
static inline void fw_dsp_mov_to_acc_low(FwDspEngine* engine, FwAcc acc, uint16_t word) {
  fw_dsp_charge(engine, FW_OP_MOV_ACC_WORD, 1u);
  const int64_t v = engine->acc[acc];
  engine->acc[acc] = (v - (int64_t)((uint64_t)v & UINT64_C(0xFFFF))) + (int64_t)word;
}

/// Writes bits 31..16 and sign-extends into ACCxU.
static inline void fw_dsp_mov_to_acc_high(FwDspEngine* engine, FwAcc acc, int16_t word) {
  fw_dsp_charge(engine, FW_OP_MOV_ACC_WORD, 1u);
  const int64_t v = engine->acc[acc];
  engine->acc[acc] = ((int64_t)word * INT64_C(65536)) + (int64_t)((uint64_t)v & UINT64_C(0xFFFF));
}

static inline uint16_t fw_dsp_mov_from_acc_low(FwDspEngine* engine, FwAcc acc) {
  fw_dsp_charge(engine, FW_OP_MOV_ACC_WORD, 1u);
  return (uint16_t)((uint64_t)engine->acc[acc] & UINT64_C(0xFFFF));
}

static inline int16_t fw_dsp_mov_from_acc_high(FwDspEngine* engine, FwAcc acc) {
  fw_dsp_charge(engine, FW_OP_MOV_ACC_WORD, 1u);
  return fw_s16_from_bits((uint16_t)(((uint64_t)engine->acc[acc] >> 16) & UINT64_C(0xFFFF)));
}

/// Bits 39..32, sign-extended.
static inline int16_t fw_dsp_mov_from_acc_upper(FwDspEngine* engine, FwAcc acc) {
  fw_dsp_charge(engine, FW_OP_MOV_ACC_WORD, 1u);
  return (int16_t)fw_asr64(engine->acc[acc], 32u);
}

// ---- MCU multiply into a W-register pair (1 cycle each).
static inline int32_t fw_dsp_mul_ss(FwDspEngine* engine, int16_t a, int16_t b) {
  fw_dsp_charge(engine, FW_OP_MUL_SS, 1u);
  return (int32_t)a * (int32_t)b;
}

static inline int32_t fw_dsp_mul_su(FwDspEngine* engine, int16_t a, uint16_t b) {
  fw_dsp_charge(engine, FW_OP_MUL_SU, 1u);
  return (int32_t)a * (int32_t)b;
}

static inline uint32_t fw_dsp_mul_uu(FwDspEngine* engine, uint16_t a, uint16_t b) {
  fw_dsp_charge(engine, FW_OP_MUL_UU, 1u);
  return (uint32_t)a * (uint32_t)b;
}

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_DSP_ENGINE_H
