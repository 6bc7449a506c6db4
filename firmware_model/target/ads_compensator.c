#include "ads_compensator.h"

#include "air_data_law.h"
#include "bridge_linearisation.h"
#include "imu_compensator.h"
#include "q31_kernels.h"
#include "q_math.h"

// z(x, y) = ((b3 x + b2) x + b1) x + b0, b_k = b_k(y), y the normalised linearised bridge code;
// result at out_exponent; y (Q31) in *y_out.
static int32_t EvaluateSurface(FwDspEngine* engine,
                               const FwSurfaceQ31* s,
                               int8_t out_exponent,
                               int32_t x_code,
                               int32_t y_code,
                               int32_t* y_out,
                               uint16_t* flags) {
  fw_dsp_charge_call_return(engine);
  const int32_t x = fw_normalise_q31(engine, x_code, 31, &s->x_norm);
  const int32_t y_linear_code =
      fw_linearised_bridge_code(engine, &s->y_linearisation, y_code, flags);
  const int32_t y = fw_normalise_q31(engine, y_linear_code, 31, &s->y_norm);
  *y_out = y;
  if (fw_dsp_test_and_clear_saturation(engine)) {
    *flags |= FW_FLAG_INPUT_SATURATED;
  }
  int32_t b[FW_ADS_SURFACE_X_DEGREE + 1u];
  for (uint8_t k = 0u; k <= FW_ADS_SURFACE_X_DEGREE; ++k) {
    b[k] = fw_horner_q31(engine, FW_ACC_A, &s->b[k], FW_ADS_SURFACE_Y_DEGREE, y);
  }
  fw_load_q31(engine, FW_ACC_A, b[FW_ADS_SURFACE_X_DEGREE]);
  fw_sftac_by(engine,
              FW_ACC_A,
              (int16_t)(s->outer_work_exponent - s->b[FW_ADS_SURFACE_X_DEGREE].work_exponent));
  int32_t z = fw_read_q31(engine, FW_ACC_A);
  for (int16_t k = (int16_t)FW_ADS_SURFACE_X_DEGREE - 1; k >= 0; --k) {
    fw_mul_q31(engine, FW_ACC_A, z, x);
    fw_load_q31(engine, FW_ACC_B, b[k]);
    fw_sftac_by(engine, FW_ACC_B, (int16_t)(s->outer_work_exponent - s->b[k].work_exponent));
    fw_dsp_add_acc(engine, FW_ACC_A);
    z = fw_read_q31(engine, FW_ACC_A);
  }
  fw_sftac_by(engine, FW_ACC_A, (int16_t)(out_exponent - s->outer_work_exponent));
  const int32_t result = fw_read_q31(engine, FW_ACC_A);
  if (fw_dsp_test_and_clear_saturation(engine)) {
    *flags |= FW_FLAG_OUTPUT_SATURATED;
  }
  return result;
}

// tau(y) = ((t3 y + t2) y + t1) y in Q15, y the normalised bridge code's high word (the exporter
// keeps every partial sum within Q15: docs/firmware-compensator.md "Hysteresis compensation").
static int16_t DieTemperatureQ15(FwDspEngine* engine, const FwSurfaceQ31* s, int32_t y_q31) {
  const int16_t y_q15 = fw_high_word(y_q31);
  fw_dsp_charge_mov(engine, 1u);
  fw_dsp_mpy(engine, FW_ACC_A, s->die_temp_q15[2], y_q15);
  fw_dsp_add_word_acc(engine, FW_ACC_A, s->die_temp_q15[1], 0);
  int16_t tau_q15 = fw_dsp_sac_r(engine, FW_ACC_A, 0);
  fw_dsp_mpy(engine, FW_ACC_A, tau_q15, y_q15);
  fw_dsp_add_word_acc(engine, FW_ACC_A, s->die_temp_q15[0], 0);
  tau_q15 = fw_dsp_sac_r(engine, FW_ACC_A, 0);
  fw_dsp_mpy(engine, FW_ACC_A, tau_q15, y_q15);
  return fw_dsp_sac_r(engine, FW_ACC_A, 0);
}

// gain(tau) = at_centre + per_tau tau, Q15 at the gain's exponent (SAC.R saturates).
static int16_t GainAt(FwDspEngine* engine, const FwGainQ15* gain, int16_t tau_q15) {
  fw_dsp_lac(engine, FW_ACC_A, gain->at_centre_q15, 0);
  fw_dsp_mac(engine, FW_ACC_A, gain->per_tau_q15, tau_q15);
  return fw_dsp_sac_r(engine, FW_ACC_A, 0);
}

// z + gain_P s_P + gain_T s_T after advancing both operators; z at `result_exponent`.
static int32_t CompensateHysteresis(FwDspEngine* engine,
                                    const FwSurfaceQ31* s,
                                    int8_t result_exponent,
                                    int32_t z,
                                    int32_t y_q31,
                                    FwPreisachQ15* pressure,
                                    FwPreisachQ15* thermal,
                                    uint16_t* flags) {
  const int16_t s_pressure =
      fw_preisach_update_q15(engine, pressure, z, result_exponent, &s->pressure.inv_span);
  const int16_t tau_q15 = DieTemperatureQ15(engine, s, y_q31);
  const int16_t s_thermal =
      fw_preisach_update_q15(engine, thermal, fw_join_words(tau_q15, 0u), 0, &s->thermal.inv_span);
  const int16_t gain_pressure_q15 = GainAt(engine, &s->pressure.gain, tau_q15);
  const int16_t gain_thermal_q15 = GainAt(engine, &s->thermal.gain, tau_q15);
  (void)fw_dsp_test_and_clear_saturation(engine);  // the travel clamp
  fw_dsp_mpy(engine, FW_ACC_A, gain_pressure_q15, s_pressure);
  fw_sftac_by(engine, FW_ACC_A, (int16_t)(result_exponent - s->pressure.gain.exponent));
  fw_dsp_mpy(engine, FW_ACC_B, gain_thermal_q15, s_thermal);
  fw_sftac_by(engine, FW_ACC_B, (int16_t)(result_exponent - s->thermal.gain.exponent));
  fw_dsp_add_acc(engine, FW_ACC_A);
  fw_load_q31(engine, FW_ACC_B, z);
  fw_dsp_add_acc(engine, FW_ACC_A);
  const int32_t result = fw_read_q31(engine, FW_ACC_A);
  if (fw_dsp_test_and_clear_saturation(engine)) {
    *flags |= FW_FLAG_OUTPUT_SATURATED;
  }
  return result;
}

// The output of one surface at `out_exponent`: the surface itself, or its pressure (at
// FW_PRESSURE_EXPONENT) through the block's law (validated per block by ads_constants.c), each
// after the hysteresis terms.
static int32_t SurfaceAndLaw(FwDspEngine* engine,
                             const FwSurfaceQ31* s,
                             int8_t out_exponent,
                             int32_t x_code,
                             int32_t y_code,
                             FwPreisachQ15* pressure,
                             FwPreisachQ15* thermal,
                             uint16_t* flags) {
  fw_dsp_charge_branch(engine, 1u);  // the law
  const int8_t result_exponent = fw_ads_surface_exponent(s->law, out_exponent);
  int32_t y_q31 = 0;
  const int32_t surface =
      EvaluateSurface(engine, s, result_exponent, x_code, y_code, &y_q31, flags);
  const int32_t z =
      CompensateHysteresis(engine, s, result_exponent, surface, y_q31, pressure, thermal, flags);
  int32_t result = z;
  if (s->law == FW_ADS_LAW_ISA_ALTITUDE) {
    result = fw_isa_altitude_q31(engine, z, flags);
  } else if (s->law == FW_ADS_LAW_CAS) {
    result = fw_cas_q31(engine, z, flags);
  } else {
    // direct: the surface is the output
  }
  return result;
}

void fw_ads_hysteresis_reset(FwAdsHysteresisState* state) {
  fw_preisach_reset_q15(&state->static_pressure);
  fw_preisach_reset_q15(&state->static_thermal);
  fw_preisach_reset_q15(&state->pitot_pressure);
  fw_preisach_reset_q15(&state->pitot_thermal);
}

void fw_ads_compensate(FwDspEngine* engine,
                       const FwAdsConstants* constants,
                       FwAdsMode mode,
                       const FwAdsRawFrame* raw,
                       FwAdsHysteresisState* state,
                       FwAdsCompensatedFrame* out) {
  fw_dsp_charge_call_return(engine);
  engine->config = fw_compensator_dsp_config();
  fw_dsp_charge_mov(engine, 1u);  // CORCON write
  (void)fw_dsp_test_and_clear_saturation(engine);
  uint16_t flags = 0u;
  if (mode == FW_ADS_MODE_RAW) {
    fw_dsp_charge_mov(engine, 4u);
    out->value[0] = raw->ps_cnt;
    out->value[1] = raw->pt_cnt;
    out->flags = flags;
    return;
  }
  out->value[0] = SurfaceAndLaw(engine,
                                &constants->altitude,
                                FW_ALTITUDE_EXPONENT,
                                raw->ps_cnt,
                                raw->ps_bridge_cnt,
                                &state->static_pressure,
                                &state->static_thermal,
                                &flags);
  out->value[1] = SurfaceAndLaw(engine,
                                &constants->airspeed,
                                FW_AIRSPEED_EXPONENT,
                                raw->pt_cnt,
                                raw->pt_bridge_cnt,
                                &state->pitot_pressure,
                                &state->pitot_thermal,
                                &flags);
  out->flags = flags;
}
