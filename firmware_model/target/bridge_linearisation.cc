#include "firmware_model/target/bridge_linearisation.h"

#include "firmware_model/target/compensated_frame.h"
#include "firmware_model/target/q31_kernels.h"
#include "firmware_model/target/q_math.h"

namespace adahrs::firmware_model {
namespace {

// Codes are the ADS1254's 24 bits: an origin and a half-width within 2^24 keep s inside int32.
constexpr uint8_t kMaxCodeLog2 = 24;

}  // namespace

int32_t LinearisedBridgeCode(DspEngine* engine,
                             const BridgeLinearisationQ& linearisation,
                             int32_t y_code,
                             uint16_t* flags) {
  engine->ChargeCallReturn();
  engine->ChargeAlu(1);  // k == 0?
  engine->ChargeBranch(1);
  if (linearisation.curvature_q13 == 0) return y_code;
  const int16_t v_q15 = HighWord(NormaliseQ31(engine, y_code, 31, linearisation.raw_norm));
  if (engine->TestAndClearSaturation()) *flags |= kFlagInputSaturated;
  const int32_t kv_q28 = engine->MulSS(linearisation.curvature_q13, v_q15);
  engine->ChargeAlu(2);  // + 2^28 on the W pair (ADD, ADDC)
  const int32_t radicand_q28 = (INT32_C(1) << 28) + kv_q28;
  engine->ChargeBranch(1);  // r < 0?
  if (radicand_q28 < 0) *flags |= kFlagInputSaturated;
  const uint16_t root_q14 =
      IntegerSqrt(engine, radicand_q28 < 0 ? 0u : static_cast<uint32_t>(radicand_q28));
  engine->ChargeAlu(2);  // (1 + root) 2^13: LSR, ADD
  const int16_t divisor_q13 = static_cast<int16_t>((1 << 13) + (root_q14 >> 1));
  engine->ChargeAlu(3);  // v 2^28 into a W pair: sign-extend, two shifts
  const DivResult quotient_q15 =
      engine->DivSD(static_cast<int32_t>(v_q15) * (INT32_C(1) << 13), divisor_q13);
  engine->ChargeAlu(6);  // q 2^(shift - 14) on a W pair (4), + origin (ADD, ADDC)
  const int64_t offset = ShiftArith(quotient_q15.quotient, 14 - linearisation.raw_norm.shift);
  return static_cast<int32_t>(linearisation.raw_norm.centre + offset);
}

ConstantsStatus BridgeLinearisationFromWords(const int16_t* words, BridgeLinearisationQ* out) {
  BridgeLinearisationQ decoded{};
  const ConstantsStatus s = NormFromWords(words, kMaxCodeLog2, &decoded.raw_norm);
  if (s != ConstantsStatus::kOk) return s;
  decoded.curvature_q13 = words[kNormWords];
  const int32_t centre = decoded.raw_norm.centre;
  const int32_t code_limit = INT32_C(1) << kMaxCodeLog2;
  if (centre >= code_limit || centre <= -code_limit) return ConstantsStatus::kOutOfRange;
  *out = decoded;
  return ConstantsStatus::kOk;
}

void BridgeLinearisationToWords(const BridgeLinearisationQ& linearisation, int16_t* words) {
  NormToWords(linearisation.raw_norm, words);
  words[kNormWords] = linearisation.curvature_q13;
}

}  // namespace adahrs::firmware_model
