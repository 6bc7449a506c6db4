#include "preisach_q15.h"

#include "q31_kernels.h"
#include "q_math.h"

#define Q15_THREE_QUARTERS ((int16_t)0x6000)

void fw_preisach_reset_q15(FwPreisachQ15* op) {
  for (uint8_t i = 0u; i < FW_PREISACH_DEPTH; ++i) {
    op->branches[i].input = 0;
    op->branches[i].state_q15 = 0;
  }
  op->depth = 0u;
  op->origin_input = 0;
  op->last_input = 0;
  op->state_q15 = 0;
  op->direction = 0;
  op->started = 0u;
}

// Begins a branch at the last input. When the stack is full, the smallest minor loop below the
// current branch is forgotten: the pair of consecutive starts (i, i + 1) closest in input, as if
// the excursion between them had not happened (the directions still alternate). Noise makes small
// loops; a major branch's start is far from its neighbours and stays.
static void PushBranch(FwDspEngine* engine, FwPreisachQ15* op) {
  fw_dsp_charge_alu(engine, 1u);
  fw_dsp_charge_branch(engine, 1u);
  if (op->depth == FW_PREISACH_DEPTH) {
    uint8_t smallest = 0u;
    uint32_t smallest_extent = UINT32_MAX;
    for (uint8_t i = 0u; (i + 2u) < FW_PREISACH_DEPTH; ++i) {
      const int64_t extent = (int64_t)op->branches[i + 1u].input - (int64_t)op->branches[i].input;
      const uint32_t magnitude = (uint32_t)((extent < 0) ? -extent : extent);
      fw_dsp_charge_alu(engine, 5u);  // 32-bit SUB, SUBB, absolute value, compare
      fw_dsp_charge_branch(engine, 1u);
      if (magnitude < smallest_extent) {
        smallest_extent = magnitude;
        smallest = i;
        fw_dsp_charge_mov(engine, 3u);
      }
    }
    for (uint8_t i = (uint8_t)(smallest + 2u); i < FW_PREISACH_DEPTH; ++i) {
      op->branches[i - 2u] = op->branches[i];
      fw_dsp_charge_mov(engine, 3u);
    }
    op->depth = (uint8_t)(op->depth - 2u);
  }
  op->branches[op->depth].input = op->last_input;
  op->branches[op->depth].state_q15 = op->state_q15;
  ++op->depth;
  fw_dsp_charge_mov(engine, 4u);
}

// Whether `input`, moving in the input's own direction `input_direction`, has reached `start`.
static bool Beyond(FwDspEngine* engine, int32_t input, int32_t start, int8_t input_direction) {
  fw_dsp_charge_alu(engine, 2u);  // 32-bit compare: SUB, SUBB
  fw_dsp_charge_branch(engine, 1u);
  return (input_direction > 0) ? (input >= start) : (input <= start);
}

// Whether `input`, moving in the input's own direction `input_direction`, has passed the virgin
// history's extreme that precedes the oldest branch: the mirror of its start about the origin,
// 2 origin - start (compared as 33-bit differences, which cannot overflow).
static bool BeyondMirror(FwDspEngine* engine,
                         const FwPreisachQ15* op,
                         int32_t input,
                         int8_t input_direction) {
  const int64_t from_origin = (int64_t)input - (int64_t)op->origin_input;
  const int64_t mirror_from_origin = (int64_t)op->origin_input - (int64_t)op->branches[0].input;
  fw_dsp_charge_alu(engine, 6u);  // two 32-bit SUB/SUBB pairs, a 33-bit compare
  fw_dsp_charge_branch(engine, 1u);
  return (input_direction > 0) ? (from_origin >= mirror_from_origin)
                               : (from_origin <= mirror_from_origin);
}

int16_t fw_preisach_update_q15(FwDspEngine* engine,
                               FwPreisachQ15* op,
                               int32_t input,
                               int8_t input_exponent,
                               const FwCoeffQ31* inv_span) {
  fw_dsp_charge_call_return(engine);
  fw_dsp_charge_alu(engine, 1u);
  fw_dsp_charge_branch(engine, 1u);
  if (op->started == 0u) {
    op->started = 1u;
    op->origin_input = input;
    op->last_input = input;
    fw_dsp_charge_mov(engine, 4u);
    return op->state_q15;
  }
  fw_dsp_charge_alu(engine, 2u);  // 32-bit compare: SUB, SUBB
  fw_dsp_charge_branch(engine, 1u);
  if (input == op->last_input) {
    return op->state_q15;
  }

  // Direction of the physical quantity: the input's, flipped by a negative inv_span.
  const int8_t input_direction = (input > op->last_input) ? (int8_t)1 : (int8_t)-1;
  const int8_t direction =
      (inv_span->mantissa_q31 < 0) ? (int8_t)(-input_direction) : input_direction;
  fw_dsp_charge_alu(engine, 2u);
  fw_dsp_charge_branch(engine, 2u);
  if ((op->direction != 0) && (direction != op->direction)) {
    PushBranch(engine, op);
  }
  op->direction = direction;
  fw_dsp_charge_mov(engine, 1u);
  op->last_input = input;
  fw_dsp_charge_mov(engine, 2u);
  // Return-point memory: beyond the previous branch's start, the minor loop is closed.
  fw_dsp_charge_alu(engine, 1u);
  fw_dsp_charge_branch(engine, 1u);
  while ((op->depth >= 2u) &&
         Beyond(engine, input, op->branches[op->depth - 2u].input, input_direction)) {
    op->depth = (uint8_t)(op->depth - 2u);
    fw_dsp_charge_alu(engine, 2u);
    fw_dsp_charge_branch(engine, 1u);
  }
  fw_dsp_charge_alu(engine, 1u);
  fw_dsp_charge_branch(engine, 1u);
  if ((op->depth == 1u) && BeyondMirror(engine, op, input, input_direction)) {
    op->depth = 0u;
  }
  // On the virgin curve the travel is measured from the origin and counts double.
  const bool virgin = (op->depth == 0u);
  const int32_t start = virgin ? op->origin_input : op->branches[op->depth - 1u].input;
  const int16_t start_state_q15 = virgin ? (int16_t)0 : op->branches[op->depth - 1u].state_q15;
  fw_dsp_charge_alu(engine, 1u);
  fw_dsp_charge_branch(engine, 1u);
  fw_dsp_charge_mov(engine, 3u);

  // t = |input - start| * |inv_span|, carried to exponent 0; 1.31 saturation clamps it at 1.
  fw_load_q31(engine, FW_ACC_A, input);
  fw_load_q31(engine, FW_ACC_B, start);
  fw_dsp_sub_acc(engine, FW_ACC_A);
  fw_dsp_charge_branch(engine, 1u);
  if (fw_dsp_mov_from_acc_upper(engine, FW_ACC_A) < 0) {
    fw_dsp_neg_acc(engine, FW_ACC_A);
  }
  const int32_t distance = fw_read_q31(engine, FW_ACC_A);
  const int32_t inv_span_magnitude =
      (inv_span->mantissa_q31 < 0) ? -inv_span->mantissa_q31 : inv_span->mantissa_q31;
  fw_dsp_charge_alu(engine, 2u);  // 32-bit NEG: SUBR, SUBBR
  fw_mul_q31(engine, FW_ACC_A, distance, inv_span_magnitude);
  fw_shift_acc(
      engine,
      FW_ACC_A,
      (int16_t)(-((int16_t)input_exponent + (int16_t)inv_span->exponent) - (virgin ? 1 : 0)));
  const int16_t travel_q15 = fw_dsp_sac(engine, FW_ACC_A, 0);

  // w = t^2 (3 - 2t) = 4 t^2 (3/4 - t/2); the final left shift by 2 saturates at 0x7FFF.
  fw_dsp_mpy(engine, FW_ACC_A, travel_q15, travel_q15);
  const int16_t travel_sq_q15 = fw_dsp_sac_r(engine, FW_ACC_A, 0);
  const int16_t factor_q15 =
      (int16_t)((int32_t)Q15_THREE_QUARTERS - (int32_t)fw_asr64((int64_t)travel_q15, 1u));
  fw_dsp_charge_alu(engine, 2u);  // ASR, SUB
  fw_dsp_mpy(engine, FW_ACC_A, travel_sq_q15, factor_q15);
  const int16_t weight_q15 = fw_dsp_sac_r(engine, FW_ACC_A, -2);

  // state = s_b - 2 d w on a branch, -d w on the virgin curve (s_b = 0); the store saturates.
  fw_dsp_lac(engine, FW_ACC_A, start_state_q15, 0);
  fw_dsp_charge_alu(engine, 1u);  // NEG of w for a rise
  fw_dsp_add_word_acc(engine,
                      FW_ACC_A,
                      (direction > 0) ? (int16_t)(-(int32_t)weight_q15) : weight_q15,
                      virgin ? (int8_t)0 : (int8_t)-1);
  op->state_q15 = fw_dsp_sac_r(engine, FW_ACC_A, 0);
  fw_dsp_charge_mov(engine, 1u);
  return op->state_q15;
}
