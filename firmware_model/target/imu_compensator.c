#include "imu_compensator.h"

#include <stdbool.h>
#include <stddef.h>

#include "q31_kernels.h"
#include "q_math.h"

#define HALF_DUTY_Q31 INT32_C(0x40000000)  // 0.5 at exponent 0

// One pass of a channel loop: pointer increments, the count's DEC and the branch back.
static void ChargeLoopStep(FwDspEngine* engine) {
  fw_dsp_charge_alu(engine, 2u);
  fw_dsp_charge_branch(engine, 1u);
}

// U = T1/T2 - 0.5 at exponent 0, floor(U 2^31); FW_FLAG_BAD_DUTY and +full scale if t1 >= t2.
static int32_t DutyQ31(FwDspEngine* engine, uint16_t t1, uint16_t t2, uint16_t* flags) {
  fw_dsp_charge_mov(engine, 2u);     // t1, t2 into W registers
  fw_dsp_charge_alu(engine, 1u);     // CP t1, t2
  fw_dsp_charge_branch(engine, 1u);  // BRA GEU to the error path (charged as taken: worst case)
  if (t1 >= t2) {
    *flags |= FW_FLAG_BAD_DUTY;
    return INT32_MAX;
  }
  fw_dsp_charge_mov(engine, 2u);  // dividend t1:0 into the W pair
  const FwDivResult high = fw_dsp_div_ud(engine, (uint32_t)t1 << 16, t2);
  fw_dsp_charge_mov(engine, 2u);  // dividend remainder:0
  const FwDivResult low = fw_dsp_div_ud(engine, (uint32_t)high.remainder << 16, t2);
  const uint32_t ratio_u32 = ((uint32_t)high.quotient << 16) | (uint32_t)low.quotient;
  fw_dsp_charge_alu(engine, 3u);  // LSR high, RRC low, SUB #0x4000 from high
  return (int32_t)(ratio_u32 >> 1) - HALF_DUTY_Q31;
}

// U = counts at exponent 23 (counts << 8), saturating.
static int32_t GyroCountsQ31(FwDspEngine* engine, int32_t counts) {
  fw_load_q31(engine, FW_ACC_A, counts);
  fw_shift_acc(engine, FW_ACC_A, -(31 - FW_GYRO_COUNT_EXPONENT));
  return fw_read_q31(engine, FW_ACC_A);
}

// T = U - xi(tau), both at u_exponent.
static int32_t ThermalQ31(FwDspEngine* engine,
                          const FwThermalConstantsQ31* c,
                          int8_t u_exponent,
                          int32_t u,
                          const uint16_t temp_cnt[FW_TEMP_SENSORS],
                          uint16_t* flags) {
  fw_dsp_charge_call_return(engine);
  const int32_t tau = fw_normalise_q31(
      engine, (int32_t)temp_cnt[c->temp_sensor], FW_TEMP_COUNT_EXPONENT, &c->temp_norm);
  if (fw_dsp_test_and_clear_saturation(engine)) {
    *flags |= FW_FLAG_INPUT_SATURATED;
  }
  (void)fw_horner_q31(engine, FW_ACC_A, &c->drift, FW_IMU_THERMAL_DEGREE, tau);
  fw_sftac_by(engine, FW_ACC_A, (int16_t)(u_exponent - c->drift.work_exponent));
  fw_load_q31(engine, FW_ACC_B, u);
  fw_dsp_sub_acc(engine, FW_ACC_B);
  return fw_read_q31(engine, FW_ACC_B);
}

// Format 3: T = U - xi(tau), xi by Horner in Q31 partial sums with tau in Q15 (SAC.R, exact for
// shift <= 15) and the coefficients pre-aligned to the working exponent on write. A step
// y tau + c_k is floor(tau yl / 2^15) (MUL.SU) + 2 yh tau (MPY) + c_k: 12 cycles where a Q31
// Horner step (fw_mul_q31, a coefficient aligned at run time, loop control) costs 25.
static int32_t ThermalQ15HornerQ31(FwDspEngine* engine,
                                   const FwThermalConstantsQ31* c,
                                   int8_t u_exponent,
                                   int32_t u,
                                   const uint16_t temp_cnt[FW_TEMP_SENSORS],
                                   uint16_t* flags) {
  fw_dsp_charge_call_return(engine);
  fw_load_q31(engine, FW_ACC_A, (int32_t)temp_cnt[c->temp_sensor]);
  fw_load_q31(engine, FW_ACC_B, c->temp_norm.centre);
  fw_dsp_sub_acc(engine, FW_ACC_A);
  fw_dsp_charge_mov(engine, 1u);  // the shift count into a W register
  fw_shift_acc(engine, FW_ACC_A, (int16_t)((int16_t)c->temp_norm.shift - FW_TEMP_COUNT_EXPONENT));
  if (fw_dsp_test_and_clear_saturation(engine)) {
    *flags |= FW_FLAG_INPUT_SATURATED;
  }
  const int16_t tau = fw_dsp_sac_r(engine, FW_ACC_A, 0);
  fw_dsp_charge_mov(engine, 1u);  // coefficient pointer
  fw_load_q31(engine, FW_ACC_A, c->drift_aligned_q31[FW_IMU_THERMAL_DEGREE]);
  for (int16_t k = (int16_t)FW_IMU_THERMAL_DEGREE - 1; k >= 0; --k) {
    const int32_t y = fw_read_q31(engine, FW_ACC_A);
    fw_dsp_charge_mov(engine, 1u);  // tau into the multiplier's operand register
    fw_load_q31(engine, FW_ACC_B, fw_dsp_mul_su(engine, tau, fw_low_word(y)));
    fw_dsp_sftac(engine, FW_ACC_B, 15);
    fw_dsp_mpy(engine, FW_ACC_A, fw_high_word(y), tau);
    fw_dsp_add_acc(engine, FW_ACC_A);
    fw_load_q31(engine, FW_ACC_B, c->drift_aligned_q31[k]);
    fw_dsp_add_acc(engine, FW_ACC_A);
  }
  fw_sftac_by(engine, FW_ACC_A, (int16_t)(u_exponent - c->drift.work_exponent));
  fw_load_q31(engine, FW_ACC_B, u);
  fw_dsp_sub_acc(engine, FW_ACC_B);
  return fw_read_q31(engine, FW_ACC_B);
}

// Ca = (T - O) * (1/S) in g.
static int32_t AccelCalibratedQ31(FwDspEngine* engine,
                                  const FwAccelScaleConstantsQ31* c,
                                  int32_t t) {
  fw_load_q31(engine, FW_ACC_A, t);
  fw_load_q31(engine, FW_ACC_B, c->offset_duty_q31);
  fw_dsp_sub_acc(engine, FW_ACC_A);
  const int32_t d = fw_read_q31(engine, FW_ACC_A);
  fw_mul_q31(engine, FW_ACC_A, d, c->inv_scale_g.mantissa_q31);
  fw_sftac_by(engine, FW_ACC_A, (int16_t)(FW_ACCEL_G_EXPONENT - c->inv_scale_g.exponent));
  return fw_read_q31(engine, FW_ACC_A);
}

// delta(tau) in Q15 at delta->exponent: the tempco terms d1 tau + d2 tau^2 + d3 tau^3 by an
// MPY/MAC chain on the sensor's Q15 powers of tau (operands MOVed into W4..W7) at the tempco
// exponent, aligned by one SFTAC and added to d0 (Q31), then rounded by SAC.R.
static int16_t ScaleDeltaQ15At(FwDspEngine* engine,
                               const FwScaleDeltaQ15* delta,
                               const int16_t tau_pow[3]) {
  fw_dsp_charge_mov(engine, 1u);  // the channel's sensor index
  fw_dsp_charge_alu(engine, 2u);  // its powers' address: index * 6 + base
  fw_dsp_charge_mov(engine, 2u);  // d1, tau
  fw_dsp_mpy(engine, FW_ACC_B, delta->d_q15[0], tau_pow[0]);
  for (uint8_t k = 1u; k < FW_IMU_SCALE_FACTOR_DEGREE; ++k) {
    fw_dsp_charge_mov(engine, 2u);  // d_k+1, tau^k+1
    fw_dsp_mac(engine, FW_ACC_B, delta->d_q15[k], tau_pow[k]);
  }
  fw_sftac_by(engine, FW_ACC_B, (int16_t)(delta->exponent - delta->tempco_exponent));
  fw_load_q31(engine, FW_ACC_A, delta->d0_q31);
  fw_dsp_add_acc(engine, FW_ACC_A);
  return fw_dsp_sac_r(engine, FW_ACC_A, 0);
}

// y F = y + y delta at y's exponent: y delta = floor(delta yl / 2^15) (MUL.SU) + 2 yh delta
// (MAC), aligned by one SFTAC of -delta->exponent, then y added.
static int32_t ScaledQ31(FwDspEngine* engine,
                         const FwScaleDeltaQ15* delta,
                         const int16_t tau_pow[3],
                         int32_t y) {
  const int16_t d = ScaleDeltaQ15At(engine, delta, tau_pow);
  fw_dsp_charge_mov(engine, 2u);  // yh, yl into W registers
  fw_load_q31(engine, FW_ACC_B, fw_dsp_mul_su(engine, d, fw_low_word(y)));
  fw_dsp_sftac(engine, FW_ACC_B, 15);
  fw_dsp_mac(engine, FW_ACC_B, fw_high_word(y), d);
  fw_sftac_by(engine, FW_ACC_B, (int16_t)(-delta->exponent));
  fw_load_q31(engine, FW_ACC_A, y);
  fw_dsp_add_acc(engine, FW_ACC_A);
  return fw_read_q31(engine, FW_ACC_A);
}

// Eq. 23 in deg/s; format 3 (`delta` not null): the normalised count times F(tau) first, so the
// cubic inverts the response at the calibration's scale whatever the temperature.
static int32_t GyroCalibratedQ31(FwDspEngine* engine,
                                 const FwGyroCubicConstantsQ31* c,
                                 int32_t t,
                                 const FwScaleDeltaQ15* delta,
                                 const int16_t tau_pow[3],
                                 uint16_t* flags) {
  fw_dsp_charge_call_return(engine);
  int32_t x = fw_normalise_q31(engine, t, FW_GYRO_COUNT_EXPONENT, &c->count_norm);
  if (fw_dsp_test_and_clear_saturation(engine)) {
    *flags |= FW_FLAG_INPUT_SATURATED;
  }
  fw_dsp_charge_branch(engine, 1u);
  if (delta != NULL) {
    x = ScaledQ31(engine, delta, tau_pow, x);
  }
  return fw_horner_q31(engine, FW_ACC_A, &c->rate, 3u, x);
}

// (a + b)/2 or (a - b)/2 without intermediate overflow: both halved first (floor each).
static int32_t HalfSumQ31(FwDspEngine* engine, int32_t a, int32_t b, bool difference) {
  fw_load_q31(engine, FW_ACC_A, a);
  fw_dsp_sftac(engine, FW_ACC_A, 1);
  fw_load_q31(engine, FW_ACC_B, b);
  fw_dsp_sftac(engine, FW_ACC_B, 1);
  if (difference) {
    fw_dsp_sub_acc(engine, FW_ACC_A);
  } else {
    fw_dsp_add_acc(engine, FW_ACC_A);
  }
  return fw_read_q31(engine, FW_ACC_A);
}

// y = M v, M entries at their own exponents, v at in_exponent, y at out_exponent. Each term is a
// fw_mul_q31 aligned by one SFTAC, added to the running sum held in a W pair.
static void MatrixVectorQ31(FwDspEngine* engine,
                            const FwCoeffQ31 m[3][3],
                            const int32_t v[3],
                            int8_t in_exponent,
                            int8_t out_exponent,
                            int32_t y[3]) {
  fw_dsp_charge_call_return(engine);
  for (uint8_t r = 0u; r < 3u; ++r) {
    int32_t sum = 0;
    for (uint8_t c = 0u; c < 3u; ++c) {
      fw_mul_q31(engine, FW_ACC_A, m[r][c].mantissa_q31, v[c]);
      fw_sftac_by(engine, FW_ACC_A, (int16_t)((out_exponent - m[r][c].exponent) - in_exponent));
      if (c > 0u) {
        fw_load_q31(engine, FW_ACC_B, sum);
        fw_dsp_add_acc(engine, FW_ACC_A);
      }
      sum = fw_read_q31(engine, FW_ACC_A);
    }
    y[r] = sum;
  }
}

// tau_s = (t_cnt[s] - centre_s) 2^-shift_s for every temperature sensor (format 3), rounded to
// Q15 (exact for shift <= 15), and its square and cube (MPY, SAC.R), stored per sensor.
static void ScaleTemperaturesQ15(FwDspEngine* engine,
                                 const FwScaleTemperatureConstantsQ31* st,
                                 const uint16_t temp_cnt[FW_TEMP_SENSORS],
                                 int16_t tau_pow[FW_TEMP_SENSORS][3],
                                 uint16_t* flags) {
  for (uint8_t s = 0u; s < FW_TEMP_SENSORS; ++s) {
    fw_load_q31(engine, FW_ACC_A, (int32_t)temp_cnt[s]);
    fw_load_q31(engine, FW_ACC_B, st->temp_norm[s].centre);
    fw_dsp_sub_acc(engine, FW_ACC_A);
    fw_dsp_charge_mov(engine, 1u);  // the shift count into a W register
    fw_shift_acc(
        engine, FW_ACC_A, (int16_t)((int16_t)st->temp_norm[s].shift - FW_TEMP_COUNT_EXPONENT));
    const int16_t tau = fw_dsp_sac_r(engine, FW_ACC_A, 0);
    fw_dsp_mpy(engine, FW_ACC_B, tau, tau);
    const int16_t tau2 = fw_dsp_sac_r(engine, FW_ACC_B, 0);
    fw_dsp_mpy(engine, FW_ACC_B, tau2, tau);
    const int16_t tau3 = fw_dsp_sac_r(engine, FW_ACC_B, 0);
    fw_dsp_charge_mov(engine, 3u);  // the three powers to RAM
    tau_pow[s][0] = tau;
    tau_pow[s][1] = tau2;
    tau_pow[s][2] = tau3;
    ChargeLoopStep(engine);
  }
  if (fw_dsp_test_and_clear_saturation(engine)) {
    *flags |= FW_FLAG_INPUT_SATURATED;
  }
}

// ca + q ca^2 in g, ca in ACCA (the pair mean): ca rounded to Q15 (SAC.R), squared (MPY Wm*Wm),
// the square (exponent 2 FW_ACCEL_G_EXPONENT) rounded to Q15, times q (MPY), aligned, added to ca.
static int32_t AccelQuadraticQ15(FwDspEngine* engine, int16_t q_q15, int8_t q_exponent) {
  const int16_t ca = fw_dsp_sac_r(engine, FW_ACC_A, 0);
  fw_dsp_mpy(engine, FW_ACC_B, ca, ca);
  const int16_t square = fw_dsp_sac_r(engine, FW_ACC_B, 0);
  fw_dsp_charge_mov(engine, 1u);  // q
  fw_dsp_mpy(engine, FW_ACC_B, q_q15, square);
  fw_sftac_by(engine, FW_ACC_B, (int16_t)(-FW_ACCEL_G_EXPONENT - (int16_t)q_exponent));
  fw_dsp_add_acc(engine, FW_ACC_A);
  return fw_read_q31(engine, FW_ACC_A);
}

// G += GS A: A rounded to Q15 (SAC.R), per row an MPY/MAC chain of the Q15 row (operands MOVed
// into W4..W7) aligned from the row's exponent to FW_RATE_EXPONENT by one SFTAC, added to G.
static void AddGSensitivityQ15(FwDspEngine* engine,
                               const FwGSensitivityQ15* gs,
                               const int32_t a_mps2[3],
                               int32_t g_dps[3]) {
  fw_dsp_charge_call_return(engine);
  int16_t a_q15[3];
  for (uint8_t i = 0u; i < 3u; ++i) {
    fw_load_q31(engine, FW_ACC_A, a_mps2[i]);
    a_q15[i] = fw_dsp_sac_r(engine, FW_ACC_A, 0);
  }
  fw_dsp_charge_mov(engine, 2u);  // row pointer and loop count
  for (uint8_t r = 0u; r < 3u; ++r) {
    fw_dsp_charge_mov(engine, 2u);
    fw_dsp_mpy(engine, FW_ACC_B, gs->m_q15[r][0], a_q15[0]);
    for (uint8_t c = 1u; c < 3u; ++c) {
      fw_dsp_charge_mov(engine, 2u);
      fw_dsp_mac(engine, FW_ACC_B, gs->m_q15[r][c], a_q15[c]);
    }
    fw_sftac_by(engine, FW_ACC_B, (int16_t)(-gs->row_exponent[r]));
    fw_load_q31(engine, FW_ACC_A, g_dps[r]);
    fw_dsp_add_acc(engine, FW_ACC_A);
    g_dps[r] = fw_read_q31(engine, FW_ACC_A);
    ChargeLoopStep(engine);
  }
}

FwDspConfig fw_compensator_dsp_config(void) {
  FwDspConfig config;
  config.integer_mode = false;
  config.unsigned_mode = false;
  config.saturate_a = true;
  config.saturate_b = true;
  config.super_saturation = false;
  config.saturate_writes = true;
  config.convergent_rounding = true;
  return config;
}

static void CopyValues(const int32_t* values, uint16_t flags, FwImuCompensatedFrame* out) {
  for (uint8_t c = 0u; c < FW_IMU_OUTPUT_VALUES; ++c) {
    out->value[c] = values[c];
  }
  out->flags = flags;
}

void fw_imu_compensate(FwDspEngine* engine,
                       const FwImuConstants* constants,
                       FwImuMode mode,
                       const FwImuRawFrame* raw,
                       FwImuCompensatedFrame* out) {
  fw_dsp_charge_call_return(engine);
  engine->config = fw_compensator_dsp_config();
  fw_dsp_charge_mov(engine, 1u);  // CORCON write
  (void)fw_dsp_test_and_clear_saturation(engine);
  uint16_t flags = 0u;

  int32_t u[FW_IMU_CHANNELS];
  for (uint8_t c = 0u; c < FW_ACCEL_CHANNELS; ++c) {
    u[c] = DutyQ31(engine, raw->t1_cnt[c], raw->t2_cnt[c], &flags);
    ChargeLoopStep(engine);
  }
  for (uint8_t g = 0u; g < FW_GYRO_CHANNELS; ++g) {
    u[FW_ACCEL_CHANNELS + g] = GyroCountsQ31(engine, raw->gyro_cnt[g]);
    ChargeLoopStep(engine);
  }
  if (fw_dsp_test_and_clear_saturation(engine)) {
    flags |= FW_FLAG_INPUT_SATURATED;
  }
  if (mode == FW_IMU_MODE_RAW) {
    CopyValues(u, flags, out);
    return;
  }

  // The format-3 switch, tested once: the two formats run separate copies of the stages below.
  const FwScaleTemperatureConstantsQ31* st = &constants->scale_temperature;
  const bool format3 = (st->enabled != 0u);
  fw_dsp_charge_mov(engine, 1u);  // enabled flag
  fw_dsp_charge_branch(engine, 1u);
  int32_t t[FW_IMU_CHANNELS];
  for (uint8_t c = 0u; c < FW_IMU_CHANNELS; ++c) {
    const int8_t u_exponent =
        (c < FW_ACCEL_CHANNELS) ? (int8_t)FW_DUTY_EXPONENT : (int8_t)FW_GYRO_COUNT_EXPONENT;
    const FwThermalConstantsQ31* thermal = &constants->thermal[c];
    t[c] = format3 ? ThermalQ15HornerQ31(engine, thermal, u_exponent, u[c], raw->temp_cnt, &flags)
                   : ThermalQ31(engine, thermal, u_exponent, u[c], raw->temp_cnt, &flags);
    ChargeLoopStep(engine);
  }
  if (fw_dsp_test_and_clear_saturation(engine)) {
    flags |= FW_FLAG_OUTPUT_SATURATED;
  }
  if (mode == FW_IMU_MODE_THERMAL) {
    CopyValues(t, flags, out);
    return;
  }

  // Format 3: the temperature sensors normalised once, then F scales each accelerometer's value
  // and each gyro's count before its cubic.
  int16_t tau_pow[FW_TEMP_SENSORS][3] = {0};
  if (format3) {
    ScaleTemperaturesQ15(engine, st, raw->temp_cnt, tau_pow, &flags);
  }
  int32_t cal[FW_IMU_CHANNELS];
  for (uint8_t c = 0u; c < FW_ACCEL_CHANNELS; ++c) {
    cal[c] = AccelCalibratedQ31(engine, &constants->accel[c], t[c]);
    fw_dsp_charge_branch(engine, 1u);
    if (format3) {
      cal[c] = ScaledQ31(engine, &st->delta[c], tau_pow[constants->thermal[c].temp_sensor], cal[c]);
    }
    ChargeLoopStep(engine);
  }
  // Format 3: a saturated accelerometer product is an output's, not the gyro inputs' below.
  if (format3 && fw_dsp_test_and_clear_saturation(engine)) {
    flags |= FW_FLAG_OUTPUT_SATURATED;
  }
  for (uint8_t g = 0u; g < FW_GYRO_CHANNELS; ++g) {
    const uint8_t c = (uint8_t)(FW_ACCEL_CHANNELS + g);
    const FwScaleDeltaQ15* delta = format3 ? &st->delta[c] : NULL;
    cal[c] = GyroCalibratedQ31(engine,
                               &constants->gyro[g],
                               t[c],
                               delta,
                               tau_pow[constants->thermal[c].temp_sensor],
                               &flags);
    ChargeLoopStep(engine);
  }
  if (fw_dsp_test_and_clear_saturation(engine)) {
    flags |= FW_FLAG_OUTPUT_SATURATED;
  }
  if (mode == FW_IMU_MODE_SENSOR_CALIBRATED) {
    CopyValues(cal, flags, out);
    return;
  }

  // Accelerometer channels of body axes x, y, z: (ch1, ch2) in az1 ax1 ay1 az2 ax2 ay2 order.
  static const uint8_t kPairOfAxis[3][2] = {{1u, 4u}, {2u, 5u}, {0u, 3u}};
  int32_t ca_g[3];
  int32_t half_difference_g[3];
  for (uint8_t axis = 0u; axis < 3u; ++axis) {
    const int32_t ch1 = cal[kPairOfAxis[axis][0]];
    const int32_t ch2 = cal[kPairOfAxis[axis][1]];
    ca_g[axis] = HalfSumQ31(engine, ch1, ch2, false);
    if (format3) {
      ca_g[axis] = AccelQuadraticQ15(
          engine, st->accel_quadratic_q15[axis], st->accel_quadratic[axis].exponent);
    }
    half_difference_g[axis] = HalfSumQ31(engine, ch1, ch2, true);
  }
  int32_t a_mps2[3];
  int32_t g_dps[3];
  MatrixVectorQ31(engine, constants->ca, ca_g, FW_ACCEL_G_EXPONENT, FW_ACCEL_MPS2_EXPONENT, a_mps2);
  MatrixVectorQ31(
      engine, constants->cg, &cal[FW_ACCEL_CHANNELS], FW_RATE_EXPONENT, FW_RATE_EXPONENT, g_dps);
  if (format3) {
    AddGSensitivityQ15(engine, &st->gs_q15, a_mps2, g_dps);
  }
  if (fw_dsp_test_and_clear_saturation(engine)) {
    flags |= FW_FLAG_OUTPUT_SATURATED;
  }
  for (uint8_t i = 0u; i < 3u; ++i) {
    out->value[i] = a_mps2[i];
    out->value[3u + i] = g_dps[i];
    out->value[6u + i] = half_difference_g[i];
  }
  out->flags = flags;
}
