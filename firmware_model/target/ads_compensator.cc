#include "firmware_model/target/ads_compensator.h"

#include "firmware_model/target/air_data_law.h"
#include "firmware_model/target/imu_compensator.h"
#include "firmware_model/target/q31_kernels.h"
#include "firmware_model/target/q_math.h"

namespace adahrs::firmware_model {
namespace {

// z(x, y) = ((b3 x + b2) x + b1) x + b0, b_k = b_k(y), y the normalised linearised bridge code;
// result at out_exponent; y (Q31) in *y_out.
int32_t EvaluateSurface(DspEngine* engine,
                        const SurfaceQ31& s,
                        int8_t out_exponent,
                        int32_t x_code,
                        int32_t y_code,
                        int32_t* y_out,
                        uint16_t* flags) {
  engine->ChargeCallReturn();
  const int32_t x = NormaliseQ31(engine, x_code, 31, s.x_norm);
  const int32_t y_linear_code = LinearisedBridgeCode(engine, s.y_linearisation, y_code, flags);
  const int32_t y = NormaliseQ31(engine, y_linear_code, 31, s.y_norm);
  *y_out = y;
  if (engine->TestAndClearSaturation()) *flags |= kFlagInputSaturated;
  int32_t b[kAdsSurfaceXDegree + 1];
  for (uint8_t k = 0; k <= kAdsSurfaceXDegree; ++k) {
    b[k] = HornerQ31(engine, Acc::kA, s.b[k], kAdsSurfaceYDegree, y);
  }
  LoadQ31(engine, Acc::kA, b[kAdsSurfaceXDegree]);
  SftacBy(engine, Acc::kA, s.outer_work_exponent - s.b[kAdsSurfaceXDegree].work_exponent);
  int32_t z = ReadQ31(engine, Acc::kA);
  for (int32_t k = kAdsSurfaceXDegree - 1; k >= 0; --k) {
    MulQ31(engine, Acc::kA, z, x);
    LoadQ31(engine, Acc::kB, b[k]);
    SftacBy(engine, Acc::kB, s.outer_work_exponent - s.b[k].work_exponent);
    engine->AddAcc(Acc::kA);
    z = ReadQ31(engine, Acc::kA);
  }
  SftacBy(engine, Acc::kA, out_exponent - s.outer_work_exponent);
  const int32_t result = ReadQ31(engine, Acc::kA);
  if (engine->TestAndClearSaturation()) *flags |= kFlagOutputSaturated;
  return result;
}

// tau(y) = ((t3 y + t2) y + t1) y in Q15, y the normalised bridge code's high word (the exporter
// keeps every partial sum within Q15: docs/firmware-compensator.md "Hysteresis compensation").
int16_t DieTemperatureQ15(DspEngine* engine, const SurfaceQ31& s, int32_t y_q31) {
  const int16_t y_q15 = HighWord(y_q31);
  engine->ChargeMov(1);
  engine->Mpy(Acc::kA, s.die_temp_q15[2], y_q15);
  engine->AddWordAcc(Acc::kA, s.die_temp_q15[1], 0);
  int16_t tau_q15 = engine->SacR(Acc::kA, 0);
  engine->Mpy(Acc::kA, tau_q15, y_q15);
  engine->AddWordAcc(Acc::kA, s.die_temp_q15[0], 0);
  tau_q15 = engine->SacR(Acc::kA, 0);
  engine->Mpy(Acc::kA, tau_q15, y_q15);
  return engine->SacR(Acc::kA, 0);
}

// gain(tau) = at_centre + per_tau tau, Q15 at the gain's exponent (SAC.R saturates).
int16_t GainAt(DspEngine* engine, const GainQ15& gain, int16_t tau_q15) {
  engine->Lac(Acc::kA, gain.at_centre_q15, 0);
  engine->Mac(Acc::kA, gain.per_tau_q15, tau_q15);
  return engine->SacR(Acc::kA, 0);
}

// z + gain_P s_P + gain_T s_T after advancing both operators; z at `result_exponent`.
int32_t CompensateHysteresis(DspEngine* engine,
                             const SurfaceQ31& s,
                             int8_t result_exponent,
                             int32_t z,
                             int32_t y_q31,
                             PreisachQ15* pressure,
                             PreisachQ15* thermal,
                             uint16_t* flags) {
  const int16_t s_pressure =
      PreisachUpdateQ15(engine, pressure, z, result_exponent, s.pressure.inv_span);
  const int16_t tau_q15 = DieTemperatureQ15(engine, s, y_q31);
  const int16_t s_thermal =
      PreisachUpdateQ15(engine, thermal, JoinWords(tau_q15, 0), 0, s.thermal.inv_span);
  const int16_t gain_pressure_q15 = GainAt(engine, s.pressure.gain, tau_q15);
  const int16_t gain_thermal_q15 = GainAt(engine, s.thermal.gain, tau_q15);
  engine->TestAndClearSaturation();  // the travel clamp
  engine->Mpy(Acc::kA, gain_pressure_q15, s_pressure);
  SftacBy(engine, Acc::kA, result_exponent - s.pressure.gain.exponent);
  engine->Mpy(Acc::kB, gain_thermal_q15, s_thermal);
  SftacBy(engine, Acc::kB, result_exponent - s.thermal.gain.exponent);
  engine->AddAcc(Acc::kA);
  LoadQ31(engine, Acc::kB, z);
  engine->AddAcc(Acc::kA);
  const int32_t result = ReadQ31(engine, Acc::kA);
  if (engine->TestAndClearSaturation()) *flags |= kFlagOutputSaturated;
  return result;
}

// The output of one surface at `out_exponent`: the surface itself, or its pressure (at
// kPressureExponent) through the block's law (validated per block by ads_constants.cc), each
// after the hysteresis terms.
int32_t SurfaceAndLaw(DspEngine* engine,
                      const SurfaceQ31& s,
                      int8_t out_exponent,
                      int32_t x_code,
                      int32_t y_code,
                      PreisachQ15* pressure,
                      PreisachQ15* thermal,
                      uint16_t* flags) {
  engine->ChargeBranch(1);  // the law
  const int8_t result_exponent = AdsSurfaceExponent(s.law, out_exponent);
  int32_t y_q31 = 0;
  const int32_t surface =
      EvaluateSurface(engine, s, result_exponent, x_code, y_code, &y_q31, flags);
  const int32_t z =
      CompensateHysteresis(engine, s, result_exponent, surface, y_q31, pressure, thermal, flags);
  if (s.law == kAdsLawIsaAltitude) return IsaAltitudeQ31(engine, z, flags);
  if (s.law == kAdsLawCas) return CasQ31(engine, z, flags);
  return z;
}

}  // namespace

void AdsHysteresisReset(AdsHysteresisState* state) {
  PreisachResetQ15(&state->static_pressure);
  PreisachResetQ15(&state->static_thermal);
  PreisachResetQ15(&state->pitot_pressure);
  PreisachResetQ15(&state->pitot_thermal);
}

void AdsCompensate(DspEngine* engine,
                   const AdsConstants& constants,
                   AdsCompensationMode mode,
                   const AdsRawFrame& raw,
                   AdsHysteresisState* state,
                   AdsCompensatedFrame* out) {
  engine->ChargeCallReturn();
  engine->set_config(CompensatorDspConfig());
  engine->ChargeMov(1);  // CORCON write
  engine->TestAndClearSaturation();
  uint16_t flags = 0;
  if (mode == AdsCompensationMode::kRaw) {
    engine->ChargeMov(4);
    out->value[0] = raw.ps_cnt;
    out->value[1] = raw.pt_cnt;
    out->flags = flags;
    return;
  }
  out->value[0] = SurfaceAndLaw(engine,
                                constants.altitude,
                                kAltitudeExponent,
                                raw.ps_cnt,
                                raw.ps_bridge_cnt,
                                &state->static_pressure,
                                &state->static_thermal,
                                &flags);
  out->value[1] = SurfaceAndLaw(engine,
                                constants.airspeed,
                                kAirspeedExponent,
                                raw.pt_cnt,
                                raw.pt_bridge_cnt,
                                &state->pitot_pressure,
                                &state->pitot_thermal,
                                &flags);
  out->flags = flags;
}

}  // namespace adahrs::firmware_model
