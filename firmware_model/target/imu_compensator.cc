#include "firmware_model/target/imu_compensator.h"

#include "firmware_model/target/q31_kernels.h"
#include "firmware_model/target/q_math.h"

namespace adahrs::firmware_model {
namespace {

constexpr int32_t kHalfDutyQ31 = INT32_C(0x40000000);  // 0.5 at exponent 0
// Accelerometer channels of body axes x, y, z: (ch1, ch2) in az1 ax1 ay1 az2 ax2 ay2 order.
constexpr uint8_t kPairOfAxis[3][2] = {{1, 4}, {2, 5}, {0, 3}};

// One pass of a channel loop: pointer increments, the count's DEC and the branch back.
void ChargeLoopStep(DspEngine* engine) {
  engine->ChargeAlu(2);
  engine->ChargeBranch(1);
}

// U = T1/T2 - 0.5 at exponent 0, floor(U 2^31); kFlagBadDuty and +full scale if t1 >= t2.
int32_t DutyQ31(DspEngine* engine, uint16_t t1, uint16_t t2, uint16_t* flags) {
  engine->ChargeMov(2);     // t1, t2 into W registers
  engine->ChargeAlu(1);     // CP t1, t2
  engine->ChargeBranch(1);  // BRA GEU to the error path (charged as taken: worst case)
  if (t1 >= t2) {
    *flags |= kFlagBadDuty;
    return INT32_MAX;
  }
  engine->ChargeMov(2);  // dividend t1:0 into the W pair
  const DivResult high = engine->DivUD(static_cast<uint32_t>(t1) << 16, t2);
  engine->ChargeMov(2);  // dividend remainder:0
  const DivResult low = engine->DivUD(static_cast<uint32_t>(high.remainder) << 16, t2);
  const uint32_t ratio_u32 =
      (static_cast<uint32_t>(high.quotient) << 16) | static_cast<uint32_t>(low.quotient);
  engine->ChargeAlu(3);  // LSR high, RRC low, SUB #0x4000 from high
  return static_cast<int32_t>(ratio_u32 >> 1) - kHalfDutyQ31;
}

// U = counts at exponent 23 (counts << 8), saturating.
int32_t GyroCountsQ31(DspEngine* engine, int32_t counts) {
  LoadQ31(engine, Acc::kA, counts);
  ShiftAcc(engine, Acc::kA, -(31 - kGyroCountExponent));
  return ReadQ31(engine, Acc::kA);
}

// T = U - xi(tau), both at u_exponent.
int32_t ThermalQ31(DspEngine* engine,
                   const ThermalConstantsQ31& c,
                   int8_t u_exponent,
                   int32_t u,
                   const uint16_t temp_cnt[kTempSensors],
                   uint16_t* flags) {
  engine->ChargeCallReturn();
  const int32_t tau =
      NormaliseQ31(engine, temp_cnt[c.temp_sensor], kTempCountExponent, c.temp_norm);
  if (engine->TestAndClearSaturation()) *flags |= kFlagInputSaturated;
  HornerQ31(engine, Acc::kA, c.drift, kImuThermalDegree, tau);
  SftacBy(engine, Acc::kA, u_exponent - c.drift.work_exponent);
  LoadQ31(engine, Acc::kB, u);
  engine->SubAcc(Acc::kB);
  return ReadQ31(engine, Acc::kB);
}

// Format 3: T = U - xi(tau), xi by Horner in Q31 partial sums with tau in Q15 (SAC.R, exact for
// shift <= 15) and the coefficients pre-aligned to the working exponent on write. A step
// y tau + c_k is floor(tau yl / 2^15) (MUL.SU) + 2 yh tau (MPY) + c_k: 12 cycles where a Q31
// Horner step (MulQ31, a coefficient aligned at run time, loop control) costs 25.
int32_t ThermalQ15HornerQ31(DspEngine* engine,
                            const ThermalConstantsQ31& c,
                            int8_t u_exponent,
                            int32_t u,
                            const uint16_t temp_cnt[kTempSensors],
                            uint16_t* flags) {
  engine->ChargeCallReturn();
  LoadQ31(engine, Acc::kA, temp_cnt[c.temp_sensor]);
  LoadQ31(engine, Acc::kB, c.temp_norm.centre);
  engine->SubAcc(Acc::kA);
  engine->ChargeMov(1);  // the shift count into a W register
  ShiftAcc(engine, Acc::kA, c.temp_norm.shift - kTempCountExponent);
  if (engine->TestAndClearSaturation()) *flags |= kFlagInputSaturated;
  const int16_t tau = engine->SacR(Acc::kA, 0);
  engine->ChargeMov(1);  // coefficient pointer
  LoadQ31(engine, Acc::kA, c.drift_aligned_q31[kImuThermalDegree]);
  for (int32_t k = kImuThermalDegree - 1; k >= 0; --k) {
    const int32_t y = ReadQ31(engine, Acc::kA);
    engine->ChargeMov(1);  // tau into the multiplier's operand register
    LoadQ31(engine, Acc::kB, engine->MulSU(tau, LowWord(y)));
    engine->Sftac(Acc::kB, 15);
    engine->Mpy(Acc::kA, HighWord(y), tau);
    engine->AddAcc(Acc::kA);
    LoadQ31(engine, Acc::kB, c.drift_aligned_q31[k]);
    engine->AddAcc(Acc::kA);
  }
  SftacBy(engine, Acc::kA, u_exponent - c.drift.work_exponent);
  LoadQ31(engine, Acc::kB, u);
  engine->SubAcc(Acc::kB);
  return ReadQ31(engine, Acc::kB);
}

// Ca = (T - O) * (1/S) in g.
int32_t AccelCalibratedQ31(DspEngine* engine, const AccelScaleConstantsQ31& c, int32_t t) {
  LoadQ31(engine, Acc::kA, t);
  LoadQ31(engine, Acc::kB, c.offset_duty_q31);
  engine->SubAcc(Acc::kA);
  const int32_t d = ReadQ31(engine, Acc::kA);
  MulQ31(engine, Acc::kA, d, c.inv_scale_g.mantissa_q31);
  SftacBy(engine, Acc::kA, kAccelGExponent - c.inv_scale_g.exponent);
  return ReadQ31(engine, Acc::kA);
}

// delta(tau) in Q15 at delta.exponent: the tempco terms d1 tau + d2 tau^2 + d3 tau^3 by an MPY/MAC
// chain on the sensor's Q15 powers of tau (operands MOVed into W4..W7) at the tempco exponent,
// aligned by one SFTAC and added to d0 (Q31), then rounded by SAC.R.
int16_t ScaleDeltaQ15At(DspEngine* engine, const ScaleDeltaQ15& delta, const int16_t tau_pow[3]) {
  engine->ChargeMov(1);  // the channel's sensor index
  engine->ChargeAlu(2);  // its powers' address: index * 6 + base
  engine->ChargeMov(2);  // d1, tau
  engine->Mpy(Acc::kB, delta.d_q15[0], tau_pow[0]);
  for (uint8_t k = 1; k < kImuScaleFactorDegree; ++k) {
    engine->ChargeMov(2);  // d_k+1, tau^k+1
    engine->Mac(Acc::kB, delta.d_q15[k], tau_pow[k]);
  }
  SftacBy(engine, Acc::kB, delta.exponent - delta.tempco_exponent);
  LoadQ31(engine, Acc::kA, delta.d0_q31);
  engine->AddAcc(Acc::kA);
  return engine->SacR(Acc::kA, 0);
}

// y F = y + y delta at y's exponent: y delta = floor(delta yl / 2^15) (MUL.SU) + 2 yh delta (MAC),
// aligned by one SFTAC of -delta.exponent, then y added.
int32_t ScaledQ31(DspEngine* engine,
                  const ScaleDeltaQ15& delta,
                  const int16_t tau_pow[3],
                  int32_t y) {
  const int16_t d = ScaleDeltaQ15At(engine, delta, tau_pow);
  engine->ChargeMov(2);  // yh, yl into W registers
  LoadQ31(engine, Acc::kB, engine->MulSU(d, LowWord(y)));
  engine->Sftac(Acc::kB, 15);
  engine->Mac(Acc::kB, HighWord(y), d);
  SftacBy(engine, Acc::kB, -delta.exponent);
  LoadQ31(engine, Acc::kA, y);
  engine->AddAcc(Acc::kA);
  return ReadQ31(engine, Acc::kA);
}

// Eq. 23 in deg/s; format 3 (`factor` not null): the normalised count times F(tau) first, so the
// cubic inverts the response at the calibration's scale whatever the temperature.
int32_t GyroCalibratedQ31(DspEngine* engine,
                          const GyroCubicConstantsQ31& c,
                          int32_t t,
                          const ScaleDeltaQ15* delta,
                          const int16_t* tau_pow,
                          uint16_t* flags) {
  engine->ChargeCallReturn();
  int32_t x = NormaliseQ31(engine, t, kGyroCountExponent, c.count_norm);
  if (engine->TestAndClearSaturation()) *flags |= kFlagInputSaturated;
  engine->ChargeBranch(1);
  if (delta != nullptr) x = ScaledQ31(engine, *delta, tau_pow, x);
  return HornerQ31(engine, Acc::kA, c.rate, 3, x);
}

// (a + b)/2 or (a - b)/2 without intermediate overflow: both halved first (floor each).
int32_t HalfSumQ31(DspEngine* engine, int32_t a, int32_t b, bool difference) {
  LoadQ31(engine, Acc::kA, a);
  engine->Sftac(Acc::kA, 1);
  LoadQ31(engine, Acc::kB, b);
  engine->Sftac(Acc::kB, 1);
  if (difference) {
    engine->SubAcc(Acc::kA);
  } else {
    engine->AddAcc(Acc::kA);
  }
  return ReadQ31(engine, Acc::kA);
}

// y = M v, M entries at their own exponents, v at in_exponent, y at out_exponent. Each term is a
// MulQ31 aligned by one SFTAC, added to the running sum held in a W pair.
void MatrixVectorQ31(DspEngine* engine,
                     const CoeffQ31 m[3][3],
                     const int32_t v[3],
                     int8_t in_exponent,
                     int8_t out_exponent,
                     int32_t y[3]) {
  engine->ChargeCallReturn();
  for (uint8_t r = 0; r < 3; ++r) {
    int32_t sum = 0;
    for (uint8_t c = 0; c < 3; ++c) {
      MulQ31(engine, Acc::kA, m[r][c].mantissa_q31, v[c]);
      SftacBy(engine, Acc::kA, out_exponent - m[r][c].exponent - in_exponent);
      if (c > 0) {
        LoadQ31(engine, Acc::kB, sum);
        engine->AddAcc(Acc::kA);
      }
      sum = ReadQ31(engine, Acc::kA);
    }
    y[r] = sum;
  }
}

// tau_s = (t_cnt[s] - centre_s) 2^-shift_s for every temperature sensor (format 3), rounded to Q15
// (exact for shift <= 15), and its square and cube (MPY, SAC.R), stored per sensor.
void ScaleTemperaturesQ15(DspEngine* engine,
                          const ScaleTemperatureConstantsQ31& st,
                          const uint16_t temp_cnt[kTempSensors],
                          int16_t tau_pow[kTempSensors][3],
                          uint16_t* flags) {
  for (uint8_t s = 0; s < kTempSensors; ++s) {
    LoadQ31(engine, Acc::kA, temp_cnt[s]);
    LoadQ31(engine, Acc::kB, st.temp_norm[s].centre);
    engine->SubAcc(Acc::kA);
    engine->ChargeMov(1);  // the shift count into a W register
    ShiftAcc(engine, Acc::kA, st.temp_norm[s].shift - kTempCountExponent);
    const int16_t tau = engine->SacR(Acc::kA, 0);
    engine->Mpy(Acc::kB, tau, tau);
    const int16_t tau2 = engine->SacR(Acc::kB, 0);
    engine->Mpy(Acc::kB, tau2, tau);
    const int16_t tau3 = engine->SacR(Acc::kB, 0);
    engine->ChargeMov(3);  // the three powers to RAM
    tau_pow[s][0] = tau;
    tau_pow[s][1] = tau2;
    tau_pow[s][2] = tau3;
    ChargeLoopStep(engine);
  }
  if (engine->TestAndClearSaturation()) *flags |= kFlagInputSaturated;
}

// ca + q ca^2 in g, ca in ACCA (the pair mean): ca rounded to Q15 (SAC.R), squared (MPY Wm*Wm),
// the square (exponent 2 kAccelGExponent) rounded to Q15, times q (MPY), aligned, added to ca.
int32_t AccelQuadraticQ15(DspEngine* engine, int16_t q_q15, int8_t q_exponent) {
  const int16_t ca = engine->SacR(Acc::kA, 0);
  engine->Mpy(Acc::kB, ca, ca);
  const int16_t square = engine->SacR(Acc::kB, 0);
  engine->ChargeMov(1);  // q
  engine->Mpy(Acc::kB, q_q15, square);
  SftacBy(engine, Acc::kB, -kAccelGExponent - q_exponent);
  engine->AddAcc(Acc::kA);
  return ReadQ31(engine, Acc::kA);
}

// G += GS A: A rounded to Q15 (SAC.R), per row an MPY/MAC chain of the Q15 row (operands MOVed
// into W4..W7) aligned from the row's exponent to kRateExponent by one SFTAC, added to G.
void AddGSensitivityQ15(DspEngine* engine,
                        const GSensitivityQ15& gs,
                        const int32_t a_mps2[3],
                        int32_t g_dps[3]) {
  engine->ChargeCallReturn();
  int16_t a_q15[3];
  for (uint8_t i = 0; i < 3; ++i) {
    LoadQ31(engine, Acc::kA, a_mps2[i]);
    a_q15[i] = engine->SacR(Acc::kA, 0);
  }
  engine->ChargeMov(2);  // row pointer and loop count
  for (uint8_t r = 0; r < 3; ++r) {
    engine->ChargeMov(2);
    engine->Mpy(Acc::kB, gs.m_q15[r][0], a_q15[0]);
    for (uint8_t c = 1; c < 3; ++c) {
      engine->ChargeMov(2);
      engine->Mac(Acc::kB, gs.m_q15[r][c], a_q15[c]);
    }
    SftacBy(engine, Acc::kB, -gs.row_exponent[r]);
    LoadQ31(engine, Acc::kA, g_dps[r]);
    engine->AddAcc(Acc::kA);
    g_dps[r] = ReadQ31(engine, Acc::kA);
    ChargeLoopStep(engine);
  }
}

}  // namespace

DspConfig CompensatorDspConfig() {
  DspConfig config;
  config.integer_mode = false;
  config.unsigned_mode = false;
  config.saturate_a = true;
  config.saturate_b = true;
  config.super_saturation = false;
  config.saturate_writes = true;
  config.convergent_rounding = true;
  return config;
}

void ImuCompensate(DspEngine* engine,
                   const ImuConstants& constants,
                   ImuCompensationMode mode,
                   const ImuRawFrame& raw,
                   ImuCompensatedFrame* out) {
  engine->ChargeCallReturn();
  engine->set_config(CompensatorDspConfig());
  engine->ChargeMov(1);  // CORCON write
  engine->TestAndClearSaturation();
  uint16_t flags = 0;

  int32_t u[kImuChannels];
  for (uint8_t c = 0; c < kAccelChannels; ++c) {
    u[c] = DutyQ31(engine, raw.t1_cnt[c], raw.t2_cnt[c], &flags);
    ChargeLoopStep(engine);
  }
  for (uint8_t g = 0; g < kGyroChannels; ++g) {
    u[kAccelChannels + g] = GyroCountsQ31(engine, raw.gyro_cnt[g]);
    ChargeLoopStep(engine);
  }
  if (engine->TestAndClearSaturation()) flags |= kFlagInputSaturated;
  if (mode == ImuCompensationMode::kRaw) {
    for (uint8_t c = 0; c < kImuChannels; ++c) out->value[c] = u[c];
    out->flags = flags;
    return;
  }

  // The format-3 switch, tested once: the two formats run separate copies of the stages below.
  const ScaleTemperatureConstantsQ31& st = constants.scale_temperature;
  engine->ChargeMov(1);  // enabled flag
  engine->ChargeBranch(1);
  int32_t t[kImuChannels];
  for (uint8_t c = 0; c < kImuChannels; ++c) {
    const int8_t u_exponent = c < kAccelChannels ? kDutyExponent : kGyroCountExponent;
    const ThermalConstantsQ31& thermal = constants.thermal[c];
    t[c] = st.enabled != 0
               ? ThermalQ15HornerQ31(engine, thermal, u_exponent, u[c], raw.temp_cnt, &flags)
               : ThermalQ31(engine, thermal, u_exponent, u[c], raw.temp_cnt, &flags);
    ChargeLoopStep(engine);
  }
  if (engine->TestAndClearSaturation()) flags |= kFlagOutputSaturated;
  if (mode == ImuCompensationMode::kThermal) {
    for (uint8_t c = 0; c < kImuChannels; ++c) out->value[c] = t[c];
    out->flags = flags;
    return;
  }

  // Format 3: the temperature sensors normalised once, then F scales each accelerometer's value
  // and each gyro's count before its cubic.
  int16_t tau_pow[kTempSensors][3] = {};
  if (st.enabled != 0) ScaleTemperaturesQ15(engine, st, raw.temp_cnt, tau_pow, &flags);
  int32_t cal[kImuChannels];
  for (uint8_t c = 0; c < kAccelChannels; ++c) {
    cal[c] = AccelCalibratedQ31(engine, constants.accel[c], t[c]);
    engine->ChargeBranch(1);
    if (st.enabled != 0) {
      cal[c] = ScaledQ31(engine, st.delta[c], tau_pow[constants.thermal[c].temp_sensor], cal[c]);
    }
    ChargeLoopStep(engine);
  }
  // Format 3: a saturated accelerometer product is an output's, not the gyro inputs' below.
  if (st.enabled != 0 && engine->TestAndClearSaturation()) flags |= kFlagOutputSaturated;
  for (uint8_t g = 0; g < kGyroChannels; ++g) {
    const uint8_t c = static_cast<uint8_t>(kAccelChannels + g);
    const ScaleDeltaQ15* delta = st.enabled != 0 ? &st.delta[c] : nullptr;
    cal[c] = GyroCalibratedQ31(
        engine, constants.gyro[g], t[c], delta, tau_pow[constants.thermal[c].temp_sensor], &flags);
    ChargeLoopStep(engine);
  }
  if (engine->TestAndClearSaturation()) flags |= kFlagOutputSaturated;
  if (mode == ImuCompensationMode::kSensorCalibrated) {
    for (uint8_t c = 0; c < kImuChannels; ++c) out->value[c] = cal[c];
    out->flags = flags;
    return;
  }

  int32_t ca_g[3];
  int32_t half_difference_g[3];
  for (uint8_t axis = 0; axis < 3; ++axis) {
    const int32_t ch1 = cal[kPairOfAxis[axis][0]];
    const int32_t ch2 = cal[kPairOfAxis[axis][1]];
    ca_g[axis] = HalfSumQ31(engine, ch1, ch2, false);
    if (st.enabled != 0) {
      ca_g[axis] = AccelQuadraticQ15(
          engine, st.accel_quadratic_q15[axis], st.accel_quadratic[axis].exponent);
    }
    half_difference_g[axis] = HalfSumQ31(engine, ch1, ch2, true);
  }
  int32_t a_mps2[3];
  int32_t g_dps[3];
  MatrixVectorQ31(engine, constants.ca, ca_g, kAccelGExponent, kAccelMps2Exponent, a_mps2);
  MatrixVectorQ31(engine, constants.cg, cal + kAccelChannels, kRateExponent, kRateExponent, g_dps);
  if (st.enabled != 0) {
    AddGSensitivityQ15(engine, st.gs_q15, a_mps2, g_dps);
  }
  if (engine->TestAndClearSaturation()) flags |= kFlagOutputSaturated;
  for (uint8_t i = 0; i < 3; ++i) {
    out->value[i] = a_mps2[i];
    out->value[3 + i] = g_dps[i];
    out->value[6 + i] = half_difference_g[i];
  }
  out->flags = flags;
}

}  // namespace adahrs::firmware_model
