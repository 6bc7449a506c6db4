#include "firmware_model/target/last_extreme_q15.h"

#include "firmware_model/target/q31_kernels.h"

namespace adahrs::firmware_model {
namespace {

constexpr int16_t kQ15ThreeQuarters = 0x6000;

}  // namespace

void LastExtremeResetQ15(LastExtremeQ15* op) {
  op->last_input = 0;
  op->extreme_input = 0;
  op->extreme_state_q15 = 0;
  op->state_q15 = 0;
  op->direction = 0;
  op->started = 0;
}

int16_t LastExtremeUpdateQ15(DspEngine* engine, LastExtremeQ15* op, int32_t input,
                             int8_t input_exponent, const CoeffQ31& inv_span) {
  engine->ChargeCallReturn();
  engine->ChargeAlu(1);
  engine->ChargeBranch(1);
  if (op->started == 0) {
    op->started = 1;
    op->last_input = input;
    op->extreme_input = input;
    engine->ChargeMov(5);
    return op->state_q15;
  }
  engine->ChargeAlu(2);  // 32-bit compare: SUB, SUBB
  engine->ChargeBranch(1);
  if (input == op->last_input) return op->state_q15;

  // Direction of the physical quantity: the input's, flipped by a negative inv_span.
  int8_t direction = input > op->last_input ? 1 : -1;
  if (inv_span.mantissa_q31 < 0) direction = static_cast<int8_t>(-direction);
  engine->ChargeAlu(2);
  engine->ChargeBranch(2);
  if (direction != op->direction) {
    op->direction = direction;
    op->extreme_input = op->last_input;
    op->extreme_state_q15 = op->state_q15;
    engine->ChargeMov(4);
  }
  op->last_input = input;
  engine->ChargeMov(2);

  // t = |input - extreme| * |inv_span|, carried to exponent 0; 1.31 saturation clamps it at 1.
  LoadQ31(engine, Acc::kA, input);
  LoadQ31(engine, Acc::kB, op->extreme_input);
  engine->SubAcc(Acc::kA);
  engine->ChargeBranch(1);
  if (engine->MovFromAccUpper(Acc::kA) < 0) engine->NegAcc(Acc::kA);
  const int32_t distance = ReadQ31(engine, Acc::kA);
  const int32_t inv_span_magnitude =
      inv_span.mantissa_q31 < 0 ? -inv_span.mantissa_q31 : inv_span.mantissa_q31;
  engine->ChargeAlu(2);  // 32-bit NEG: SUBR, SUBBR
  MulQ31(engine, Acc::kA, distance, inv_span_magnitude);
  ShiftAcc(engine, Acc::kA, -(input_exponent + inv_span.exponent));
  const int16_t travel_q15 = engine->Sac(Acc::kA, 0);

  // w = t^2 (3 - 2t) = 4 t^2 (3/4 - t/2); the final left shift by 2 saturates at 0x7FFF.
  engine->Mpy(Acc::kA, travel_q15, travel_q15);
  const int16_t travel_sq_q15 = engine->SacR(Acc::kA, 0);
  const int16_t factor_q15 = static_cast<int16_t>(kQ15ThreeQuarters - (travel_q15 >> 1));
  engine->ChargeAlu(2);  // ASR, SUB
  engine->Mpy(Acc::kA, travel_sq_q15, factor_q15);
  const int16_t weight_q15 = engine->SacR(Acc::kA, -2);

  // state = s_ext - w s_ext + target w, target = -direction: exactly s_ext while w = 0, so the
  // reversals of input noise do not wear the state down.
  engine->Lac(Acc::kA, op->extreme_state_q15, 0);
  engine->Msc(Acc::kA, weight_q15, op->extreme_state_q15);
  engine->ChargeAlu(1);  // NEG of w for a rise
  engine->AddWordAcc(Acc::kA, direction > 0 ? static_cast<int16_t>(-weight_q15) : weight_q15, 0);
  op->state_q15 = engine->SacR(Acc::kA, 0);
  engine->ChargeMov(1);
  return op->state_q15;
}

}  // namespace adahrs::firmware_model
