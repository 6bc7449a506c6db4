#include "firmware_model/target/air_data_law.h"

#include "firmware_model/target/air_data_tables.h"
#include "firmware_model/target/compensated_frame.h"
#include "firmware_model/target/q31_kernels.h"

namespace adahrs::firmware_model {
namespace {

// T[i] + (T[i+1] - T[i]) * fraction, fraction = the low `step_log2` bits of `mantissa` as Q31.
int32_t Interpolate(
    DspEngine* engine, const int32_t* table, uint16_t i, int32_t mantissa, uint8_t step_log2) {
  engine->ChargeMov(4);  // two table entries, TBLRDL + TBLRDH each
  engine->ChargeAlu(2);  // 32-bit difference (SUB, SUBB)
  const int32_t low = table[i];
  const int32_t difference = table[i + 1] - low;
  engine->ChargeAlu(3);  // mask the low bits, shift them to Q31
  const uint32_t mask = (static_cast<uint32_t>(1) << step_log2) - 1u;
  const int32_t fraction =
      static_cast<int32_t>((static_cast<uint32_t>(mantissa) & mask) << (31u - step_log2));
  MulQ31(engine, Acc::kA, difference, fraction);
  LoadQ31(engine, Acc::kB, low);
  engine->AddAcc(Acc::kA);
  return ReadQ31(engine, Acc::kA);
}

}  // namespace

int32_t IsaAltitudeQ31(DspEngine* engine, int32_t ps_q31, uint16_t* flags) {
  engine->ChargeCallReturn();
  engine->ChargeAlu(3);  // index = mantissa >> 21, compare with the first valid entry
  engine->ChargeBranch(1);
  const uint16_t index = ps_q31 < 0 ? 0 : static_cast<uint16_t>(ps_q31 >> kIsaTableStepLog2);
  if (index < kIsaFirstValidEntry) {
    *flags |= kFlagOutputSaturated;
    engine->ChargeMov(2);
    return kIsaAltitudeTableQ31[kIsaFirstValidEntry];
  }
  return Interpolate(engine, kIsaAltitudeTableQ31, index, ps_q31, kIsaTableStepLog2);
}

int32_t CasQ31(DspEngine* engine, int32_t qc_q31, uint16_t* flags) {
  engine->ChargeCallReturn();
  engine->ChargeAlu(3);
  engine->ChargeBranch(2);
  if (qc_q31 <= 0) return 0;
  const uint16_t index = static_cast<uint16_t>(qc_q31 >> kCasTableStepLog2);
  int32_t cas_squared_q31 = 0;
  if (index >= kCasLastValidEntry) {
    *flags |= kFlagOutputSaturated;
    engine->ChargeMov(2);
    cas_squared_q31 = kCasSquaredTableQ31[kCasLastValidEntry];
  } else {
    cas_squared_q31 = Interpolate(engine, kCasSquaredTableQ31, index, qc_q31, kCasTableStepLog2);
  }
  // MulQ31 rounds down by up to 3 LSB: just above qc = 0 the interpolation can give -3.
  engine->ChargeAlu(1);
  if (cas_squared_q31 < 0) cas_squared_q31 = 0;
  // Mantissa kt^2 * 2^12 < 2^30 (CAS < 512 kt): times 4 is kt^2 * 2^14, whose root is kt * 2^7.
  engine->ChargeAlu(2);
  const uint16_t cas_q7 = IntegerSqrt(engine, static_cast<uint32_t>(cas_squared_q31) << 2);
  engine->ChargeAlu(2);  // to Q31 at kAirspeedExponent: kt * 2^22
  return static_cast<int32_t>(static_cast<uint32_t>(cas_q7) << 15);
}

}  // namespace adahrs::firmware_model
