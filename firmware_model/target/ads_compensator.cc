#include "firmware_model/target/ads_compensator.h"

#include "firmware_model/target/air_data_law.h"
#include "firmware_model/target/imu_compensator.h"
#include "firmware_model/target/q31_kernels.h"

namespace adahrs::firmware_model {
namespace {

// z(x, y) = ((b3 x + b2) x + b1) x + b0, b_k = b_k(y); result at out_exponent.
int32_t EvaluateSurface(DspEngine* engine, const SurfaceQ31& s, int8_t out_exponent, int32_t x_code,
                   int32_t y_code, uint16_t* flags) {
  engine->ChargeCallReturn();
  const int32_t x = NormaliseQ31(engine, x_code, 31, s.x_norm);
  const int32_t y = NormaliseQ31(engine, y_code, 31, s.y_norm);
  if (engine->TestAndClearSaturation()) *flags |= kFlagInputSaturated;
  int32_t b[kAdsSurfaceXDegree + 1];
  for (uint8_t k = 0; k <= kAdsSurfaceXDegree; ++k) {
    b[k] = HornerQ31(engine, Acc::kA, s.b[k], kAdsSurfaceYDegree, y);
  }
  LoadQ31(engine, Acc::kA, b[kAdsSurfaceXDegree]);
  engine->Sftac(Acc::kA, static_cast<int8_t>(s.outer_work_exponent - s.b[kAdsSurfaceXDegree].work_exponent));
  int32_t z = ReadQ31(engine, Acc::kA);
  for (int32_t k = kAdsSurfaceXDegree - 1; k >= 0; --k) {
    MulQ31(engine, Acc::kA, z, x);
    LoadQ31(engine, Acc::kB, b[k]);
    engine->Sftac(Acc::kB, static_cast<int8_t>(s.outer_work_exponent - s.b[k].work_exponent));
    engine->AddAcc(Acc::kA);
    z = ReadQ31(engine, Acc::kA);
  }
  engine->Sftac(Acc::kA, static_cast<int8_t>(out_exponent - s.outer_work_exponent));
  const int32_t result = ReadQ31(engine, Acc::kA);
  if (engine->TestAndClearSaturation()) *flags |= kFlagOutputSaturated;
  return result;
}

// The output of one surface at `out_exponent`: the surface itself, or its pressure (at
// kPressureExponent) through the block's law (validated per block by ads_constants.cc).
int32_t SurfaceAndLaw(DspEngine* engine, const SurfaceQ31& s, int8_t out_exponent, int32_t x_code,
                      int32_t y_code, uint16_t* flags) {
  engine->ChargeBranch(1);  // the law
  const int32_t z = EvaluateSurface(engine, s, AdsSurfaceExponent(s.law, out_exponent), x_code, y_code, flags);
  if (s.law == kAdsLawIsaAltitude) return IsaAltitudeQ31(engine, z, flags);
  if (s.law == kAdsLawCas) return CasQ31(engine, z, flags);
  return z;
}

}  // namespace

void AdsCompensate(DspEngine* engine, const AdsConstants& constants, AdsCompensationMode mode,
                   const AdsRawFrame& raw, AdsCompensatedFrame* out) {
  engine->ChargeCallReturn();
  engine->set_config(CompensatorDspConfig());
  engine->ChargeMov(1);  // CORCON write
  engine->TestAndClearSaturation();
  uint16_t flags = 0;
  if (mode == AdsCompensationMode::kRaw) {
    engine->ChargeMov(4);
    out->value[0] = raw.ps_code;
    out->value[1] = raw.pt_code;
    out->flags = flags;
    return;
  }
  out->value[0] = SurfaceAndLaw(engine, constants.altitude, kAltitudeExponent, raw.ps_code,
                                raw.ps_bridge_code, &flags);
  out->value[1] = SurfaceAndLaw(engine, constants.airspeed, kAirspeedExponent, raw.pt_code,
                                raw.pt_bridge_code, &flags);
  out->flags = flags;
}

}  // namespace adahrs::firmware_model
