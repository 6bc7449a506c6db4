#include "firmware_model/target/preisach_q15.h"

#include "firmware_model/target/q31_kernels.h"

namespace adahrs::firmware_model {
namespace {

constexpr int16_t kQ15ThreeQuarters = 0x6000;

}  // namespace

void PreisachResetQ15(PreisachQ15* op) {
  for (BranchStartQ15& b : op->branches) b = BranchStartQ15{0, 0};
  op->depth = 0;
  op->origin_input = 0;
  op->last_input = 0;
  op->state_q15 = 0;
  op->direction = 0;
  op->started = 0;
}

namespace {

// Begins a branch at the last input. When the stack is full, the smallest minor loop below the
// current branch is forgotten: the pair of consecutive starts (i, i + 1) closest in input, as if
// the excursion between them had not happened (the directions still alternate). Noise makes small
// loops; a major branch's start is far from its neighbours and stays.
void PushBranch(DspEngine* engine, PreisachQ15* op) {
  engine->ChargeAlu(1);
  engine->ChargeBranch(1);
  if (op->depth == kPreisachDepth) {
    uint8_t smallest = 0;
    uint32_t smallest_extent = UINT32_MAX;
    for (uint8_t i = 0; i + 2 < kPreisachDepth; ++i) {
      const int64_t extent =
          static_cast<int64_t>(op->branches[i + 1].input) - op->branches[i].input;
      const uint32_t magnitude = static_cast<uint32_t>(extent < 0 ? -extent : extent);
      engine->ChargeAlu(5);  // 32-bit SUB, SUBB, absolute value, compare
      engine->ChargeBranch(1);
      if (magnitude < smallest_extent) {
        smallest_extent = magnitude;
        smallest = i;
        engine->ChargeMov(3);
      }
    }
    for (uint8_t i = static_cast<uint8_t>(smallest + 2); i < kPreisachDepth; ++i) {
      op->branches[i - 2] = op->branches[i];
      engine->ChargeMov(3);
    }
    op->depth = static_cast<uint8_t>(op->depth - 2);
  }
  op->branches[op->depth] = BranchStartQ15{op->last_input, op->state_q15};
  ++op->depth;
  engine->ChargeMov(4);
}

// Whether `input`, moving in the input's own direction `input_direction`, has reached `start`.
bool Beyond(DspEngine* engine, int32_t input, int32_t start, int8_t input_direction) {
  engine->ChargeAlu(2);  // 32-bit compare: SUB, SUBB
  engine->ChargeBranch(1);
  return input_direction > 0 ? input >= start : input <= start;
}

// Whether `input`, moving in the input's own direction `input_direction`, has passed the virgin
// history's extreme that precedes the oldest branch: the mirror of its start about the origin,
// 2 origin - start (compared as 33-bit differences, which cannot overflow).
bool BeyondMirror(DspEngine* engine, const PreisachQ15* op, int32_t input, int8_t input_direction) {
  const int64_t from_origin = static_cast<int64_t>(input) - op->origin_input;
  const int64_t mirror_from_origin = static_cast<int64_t>(op->origin_input) - op->branches[0].input;
  engine->ChargeAlu(6);  // two 32-bit SUB/SUBB pairs, a 33-bit compare
  engine->ChargeBranch(1);
  return input_direction > 0 ? from_origin >= mirror_from_origin
                             : from_origin <= mirror_from_origin;
}

}  // namespace

int16_t PreisachUpdateQ15(DspEngine* engine,
                          PreisachQ15* op,
                          int32_t input,
                          int8_t input_exponent,
                          const CoeffQ31& inv_span) {
  engine->ChargeCallReturn();
  engine->ChargeAlu(1);
  engine->ChargeBranch(1);
  if (op->started == 0) {
    op->started = 1;
    op->origin_input = input;
    op->last_input = input;
    engine->ChargeMov(4);
    return op->state_q15;
  }
  engine->ChargeAlu(2);  // 32-bit compare: SUB, SUBB
  engine->ChargeBranch(1);
  if (input == op->last_input) return op->state_q15;

  // Direction of the physical quantity: the input's, flipped by a negative inv_span.
  const int8_t input_direction = input > op->last_input ? 1 : -1;
  const int8_t direction =
      inv_span.mantissa_q31 < 0 ? static_cast<int8_t>(-input_direction) : input_direction;
  engine->ChargeAlu(2);
  engine->ChargeBranch(2);
  if (op->direction != 0 && direction != op->direction) PushBranch(engine, op);
  op->direction = direction;
  engine->ChargeMov(1);
  op->last_input = input;
  engine->ChargeMov(2);
  // Return-point memory: beyond the previous branch's start, the minor loop is closed.
  engine->ChargeAlu(1);
  engine->ChargeBranch(1);
  while (op->depth >= 2 &&
         Beyond(engine, input, op->branches[op->depth - 2].input, input_direction)) {
    op->depth = static_cast<uint8_t>(op->depth - 2);
    engine->ChargeAlu(2);
    engine->ChargeBranch(1);
  }
  engine->ChargeAlu(1);
  engine->ChargeBranch(1);
  if (op->depth == 1 && BeyondMirror(engine, op, input, input_direction)) op->depth = 0;
  // On the virgin curve the travel is measured from the origin and counts double.
  const bool virgin = op->depth == 0;
  const int32_t start = virgin ? op->origin_input : op->branches[op->depth - 1].input;
  const int16_t start_state_q15 = virgin ? int16_t{0} : op->branches[op->depth - 1].state_q15;
  engine->ChargeAlu(1);
  engine->ChargeBranch(1);
  engine->ChargeMov(3);

  // t = |input - start| * |inv_span|, carried to exponent 0; 1.31 saturation clamps it at 1.
  LoadQ31(engine, Acc::kA, input);
  LoadQ31(engine, Acc::kB, start);
  engine->SubAcc(Acc::kA);
  engine->ChargeBranch(1);
  if (engine->MovFromAccUpper(Acc::kA) < 0) engine->NegAcc(Acc::kA);
  const int32_t distance = ReadQ31(engine, Acc::kA);
  const int32_t inv_span_magnitude =
      inv_span.mantissa_q31 < 0 ? -inv_span.mantissa_q31 : inv_span.mantissa_q31;
  engine->ChargeAlu(2);  // 32-bit NEG: SUBR, SUBBR
  MulQ31(engine, Acc::kA, distance, inv_span_magnitude);
  ShiftAcc(engine, Acc::kA, -(input_exponent + inv_span.exponent) - (virgin ? 1 : 0));
  const int16_t travel_q15 = engine->Sac(Acc::kA, 0);

  // w = t^2 (3 - 2t) = 4 t^2 (3/4 - t/2); the final left shift by 2 saturates at 0x7FFF.
  engine->Mpy(Acc::kA, travel_q15, travel_q15);
  const int16_t travel_sq_q15 = engine->SacR(Acc::kA, 0);
  const int16_t factor_q15 = static_cast<int16_t>(kQ15ThreeQuarters - (travel_q15 >> 1));
  engine->ChargeAlu(2);  // ASR, SUB
  engine->Mpy(Acc::kA, travel_sq_q15, factor_q15);
  const int16_t weight_q15 = engine->SacR(Acc::kA, -2);

  // state = s_b - 2 d w on a branch, -d w on the virgin curve (s_b = 0); the store saturates.
  engine->Lac(Acc::kA, start_state_q15, 0);
  engine->ChargeAlu(1);  // NEG of w for a rise
  engine->AddWordAcc(Acc::kA,
                     direction > 0 ? static_cast<int16_t>(-weight_q15) : weight_q15,
                     static_cast<int8_t>(virgin ? 0 : -1));
  op->state_q15 = engine->SacR(Acc::kA, 0);
  engine->ChargeMov(1);
  return op->state_q15;
}

}  // namespace adahrs::firmware_model
