// The IM3 unit's calibration constants in target (fixed-point) form, and the block-wise access the
// maintenance port uses to write and read them (reference-method.md, Chapter 2 steps 2-5).
//
// Channels, in this order everywhere (reference-method.md, "The unit"):
//   0 az1, 1 ax1, 2 ay1, 3 az2, 4 ax2, 5 ay2   ADXL210E duty-cycle channels, two per body axis with
//                                            opposite polarity
//   6 gx, 7 gy, 8 gz                          ADXRS150 rate channels
// Temperature sensors: 0, 1, 2 are the gyro on-chip sensors of gx, gy, gz (16 summed 12-bit
// conversions each); every channel names the sensor that drives its thermal compensation.
//
// Stages and the formats of their values (value = mantissa * 2^(exponent - 31), fixed_coeff.h):
//   U   raw channel value: accel duty T1/T2 - 0.5 at exponent kDutyExponent (0), gyro counts at
//       kGyroCountExponent (23, i.e. counts * 2^8)
//   xi  thermal drift (Eq. 4-5, extended to a cubic): xi(tau) = k0 + k1 tau + k2 tau^2 + k3 tau^3,
//       tau = normalised temperature counts (saturating at +-1, which flags the input: beyond the
//       normalised span xi is held at its end value); evaluated at the poly's working exponent,
//       then brought to U's exponent. The reference method's quadratic is the case k3 = 0.
//   T   = U - xi, same format as U
//   Ca  accel, Eq. 12 as the reference summary states it: (T - O) / S, stored as offset O (duty,
//       exponent 0) and the reciprocal scale 1/S (g per duty, ~ +-25), result in g at
//       kAccelGExponent
//   Cg  gyro, Eq. 23: l0 + l1 x + l2 x^2 + l3 x^3, x = (T - centre) * 2^-shift, result in deg/s at
//       kRateExponent
//   A = CA * mean-pair(Ca) (Eq. 26, m/s^2), G = CG * Cg (Eq. 29, deg/s); see compensated_frame.h.
// Scale-temperature stages (constants format 3; run only when block 0x10 enables them, so a
// format-2 set computes bit for bit what it did before):
//   tau_s = (t_cnt[s] - centre_s) * 2^-shift_s, one normalisation per temperature sensor s
//   Ca_i *= F_i(tau_s(i)); the gyro's x *= F_g(tau_s(g)) before its cubic: a dimensionless scale
//       factor, cubic in tau of the sensor the channel's thermal block names, evaluated at
//       kScaleFactorExponent (|F| < 2); scaling the count first leaves the cubic a
//       temperature-free response to invert (the sensitivity tempco scales the gyro's
//       nonlinearity with its rate)
//   ca_axis += q_axis ca_axis^2 after the pair mean (accelerometer second-order nonlinearity)
//   G = CG * Cg + GS * A, GS in deg/s per m/s^2 (gyro g-sensitivity on the compensated A)
//   The blocks hold Q31 words; a write derives the Q15 forms the compensator runs (F - 1, q, GS)
//   and the thermal coefficients aligned to their working exponent.
//
// Blocks (id: content, length in int16 words; layouts in fixed_coeff.h):
//   0x01..0x09 thermal, channel id-1: [temperature sensor 0..2][InputNormQ31 tau (shift <= 16)]
//              [PolyQ31 degree 3 (xi)]                                           17 words
//   0x0A       accelerometer offsets and scales: 6 x ([offset duty Q31 hi][lo][CoeffQ31 1/S])
//                                                                                30 words
//   0x0B..0x0D gyro x, y, z cubic: [InputNormQ31 on T (shift <= 23)][PolyQ31 degree 3, working
//              exponent must equal kRateExponent]                                  16 words
//   0x0E       CA, row-major 3x3 CoeffQ31 (m/s^2 per g)                             27 words
//   0x0F       CG, row-major 3x3 CoeffQ31 (deg/s per deg/s)                         27 words
//   0x10       format-3 switch and temperature normalisation: [enabled 0|1]
//              3 x [InputNormQ31 tau_s (shift <= 16)]                                10 words
//   0x11..0x19 scale factor F of channel id-0x11: [PolyQ31 degree 3, working exponent
//              kScaleFactorExponent]                                                  13 words
//   0x1A       accelerometer nonlinearity q, 3 x CoeffQ31 (g per g^2)                  9 words
//   0x1B       GS, row-major 3x3 CoeffQ31 (deg/s per m/s^2)                          27 words
// Blocks 0x01..0x0F are the format-2 set and must all be written before a commit; 0x10..0x1B
// are written all together or not at all (maintenance_handler.h).
// A write validates the whole block first and changes nothing unless it returns kOk.
// Not modelled: run-time bias estimation, and any constants version or CRC (the maintenance
// handler's).
#pragma once

#include <cstdint>

#include "firmware_model/target/fixed_coeff.h"

namespace adahrs::firmware_model {

inline constexpr uint8_t kAccelChannels = 6;
inline constexpr uint8_t kGyroChannels = 3;
inline constexpr uint8_t kImuChannels = kAccelChannels + kGyroChannels;
inline constexpr uint8_t kTempSensors = 3;

/// Exponents of the stage formats (value = mantissa * 2^(exponent - 31)).
inline constexpr int8_t kDutyExponent = 0;         ///< duty, |U| < 1
inline constexpr int8_t kGyroCountExponent = 23;   ///< gyro counts, |U| < 2^23 (LSB 1/256 count)
inline constexpr int8_t kTempCountExponent = 31;   ///< temperature counts, raw integer
inline constexpr int8_t kAccelGExponent = 4;       ///< specific force in g, |Ca| < 16 g
inline constexpr int8_t kAccelMps2Exponent = 8;    ///< specific force in m/s^2, |A| < 256 m/s^2
inline constexpr int8_t kRateExponent = 8;         ///< angular rate in deg/s, |G| < 256 deg/s
inline constexpr int8_t kScaleFactorExponent = 1;  ///< dimensionless scale factor, |F| < 2

/// Rated input envelope used by the overflow check of the cross-axis matrices (Table 5).
inline constexpr int32_t kRatedAccel_g = 10;
inline constexpr int32_t kRatedRate_dps = 150;
inline constexpr int32_t kRatedAccel_mps2 = 99;  ///< 10 g, rounded up

/// Degree of the thermal drift polynomial xi and of the scale factors F.
inline constexpr uint8_t kImuThermalDegree = 3;
inline constexpr uint8_t kImuScaleFactorDegree = 3;

struct ThermalConstantsQ31 {
  uint8_t temp_sensor;     ///< 0..2: which temperature count drives this channel
  InputNormQ31 temp_norm;  ///< tau = (t_cnt - centre) * 2^-shift, shift <= 16
  PolyQ31 drift;           ///< xi(tau), degree kImuThermalDegree, in the channel's U units
  /// drift's mantissas aligned to its working exponent (floor, as Horner's SFTAC does), derived on
  /// write (DeriveThermalAligned): the format-3 path evaluates xi as a dot product on tau's powers.
  int32_t drift_aligned_q31[kImuThermalDegree + 1];
};

struct AccelScaleConstantsQ31 {
  int32_t offset_duty_q31;  ///< O, duty at exponent 0
  CoeffQ31 inv_scale_g;     ///< 1/S, g per duty unit
};

struct GyroCubicConstantsQ31 {
  InputNormQ31 count_norm;  ///< x = (T - centre) * 2^-shift, centre at kGyroCountExponent
  PolyQ31 rate;             ///< Eq. 23 in x, deg/s, work_exponent == kRateExponent
};

/// Run-time form of a scale factor, derived from its block on write: F = 1 + delta,
/// delta(tau) = d0 + d1 tau + d2 tau^2 + d3 tau^3 at `exponent`, d0 a Q31 mantissa there and the
/// tempco terms d1..d3 Q15 mantissas at the finer `tempco_exponent` (value = d 2^(e - 15)), with
/// |d0| + sum_k |d_k| below 2^exponent so no partial sum overflows for |tau| <= 1.
struct ScaleDeltaQ15 {
  int32_t d0_q31;
  int16_t d_q15[kImuScaleFactorDegree];  ///< d1..d3
  int8_t exponent;                       ///< -16..2
  int8_t tempco_exponent;                ///< exponent - 16 .. exponent
};

/// Run-time form of GS, derived from block 0x1B on write: Q15 mantissas at one exponent per row
/// (value = m 2^(row_exponent - 15)), each row's sum_j |m| <= 32767.
struct GSensitivityQ15 {
  int16_t m_q15[3][3];
  int8_t row_exponent[3];  ///< -16..2
};

/// The format-3 stages (blocks 0x10..0x1B), and the Q15 forms the compensator runs, derived on
/// write (DeriveScaleDelta, DeriveGSensitivity).
struct ScaleTemperatureConstantsQ31 {
  uint8_t enabled;                       ///< 0: skipped (a format-2 set), 1: run
  InputNormQ31 temp_norm[kTempSensors];  ///< tau_s, shift <= 16
  PolyQ31 scale[kImuChannels];           ///< F_c(tau), work_exponent == kScaleFactorExponent
  CoeffQ31 accel_quadratic[3];           ///< q per body axis, g per g^2
  CoeffQ31 gs[3][3];                     ///< GS, deg/s per m/s^2
  ScaleDeltaQ15 delta[kImuChannels];     ///< F_c - 1, derived from scale[c]
  int16_t accel_quadratic_q15[3];        ///< q rounded to Q15 at accel_quadratic[axis].exponent
  GSensitivityQ15 gs_q15;                ///< derived from gs
};

struct ImuConstants {
  ThermalConstantsQ31 thermal[kImuChannels];
  AccelScaleConstantsQ31 accel[kAccelChannels];
  GyroCubicConstantsQ31 gyro[kGyroChannels];
  CoeffQ31 ca[3][3];  ///< CA, A_mps2 = CA * Ca_g
  CoeffQ31 cg[3][3];  ///< CG, G_dps = CG * Cg_dps
  ScaleTemperatureConstantsQ31 scale_temperature;
};

/// Block ids of the IMU constant set.
enum ImuBlockId : uint8_t {
  kImuBlockThermalFirst = 0x01,  ///< 0x01..0x09: thermal, channel = id - 0x01
  kImuBlockThermalLast = 0x09,
  kImuBlockAccelOffsetScale = 0x0A,
  kImuBlockGyroCubicFirst = 0x0B,  ///< 0x0B..0x0D: gyro x, y, z
  kImuBlockGyroCubicLast = 0x0D,
  kImuBlockCa = 0x0E,
  kImuBlockCg = 0x0F,
  kImuBlockScaleSwitch = 0x10,       ///< format-3 switch and temperature normalisations
  kImuBlockScaleFactorFirst = 0x11,  ///< 0x11..0x19: F, channel = id - 0x11
  kImuBlockScaleFactorLast = 0x19,
  kImuBlockAccelQuadratic = 0x1A,
  kImuBlockGs = 0x1B,
};
/// The format-2 set is 0x01..0x0F; the format-3 blocks are 0x10..kImuBlockLast.
inline constexpr uint8_t kImuBlockLast = kImuBlockGs;

inline constexpr uint8_t kImuThermalBlockWords = 1 + kNormWords + PolyWords(kImuThermalDegree);
inline constexpr uint8_t kImuAccelBlockWords = kAccelChannels * (2 + kCoeffWords);
inline constexpr uint8_t kImuGyroBlockWords = kNormWords + PolyWords(3);
inline constexpr uint8_t kImuMatrixBlockWords = 9 * kCoeffWords;
inline constexpr uint8_t kImuScaleSwitchBlockWords = 1 + kTempSensors * kNormWords;
inline constexpr uint8_t kImuScaleFactorBlockWords = PolyWords(kImuScaleFactorDegree);
inline constexpr uint8_t kImuAccelQuadraticBlockWords = 3 * kCoeffWords;
/// Longest IMU block, for callers sizing a buffer.
inline constexpr uint8_t kImuMaxBlockWords = kImuAccelBlockWords;

/// The Q15 run-time forms of the format-3 blocks (ScaleTemperatureConstantsQ31). A write of
/// block 0x11..0x1B derives them; a caller that fills the Q31 fields itself (the exporter) calls
/// DeriveScaleTemperatureQ15 afterwards. Rounding: to nearest, |error| <= 1/2 LSB of each mantissa.
void DeriveThermalAligned(ThermalConstantsQ31* thermal);
void DeriveScaleDelta(const PolyQ31& scale, ScaleDeltaQ15* delta);
void DeriveGSensitivity(const CoeffQ31 gs[3][3], GSensitivityQ15* out);
int16_t DeriveQ15(const CoeffQ31& coeff);
void DeriveScaleTemperatureQ15(ScaleTemperatureConstantsQ31* st);

/// Puts the set into its uncalibrated state: zero drift, zero offsets, zero scales, zero gyro
/// polynomials, identity matrices (so every calibrated output of an unconfigured unit reads zero),
/// and the format-3 stages off (scale factors 1, q and GS zero).
void ImuConstantsInit(ImuConstants* constants);

/// Words in block `block_id`, or 0 if the block is unknown.
uint8_t ImuConstantsBlockLength(uint8_t block_id);

/// Replaces block `block_id` from `count` words. Returns kOk, or the first reason for refusal; on
/// refusal `constants` is unchanged.
ConstantsStatus ImuConstantsWriteBlock(ImuConstants* constants,
                                       uint8_t block_id,
                                       const int16_t* words,
                                       uint8_t count);

/// Writes block `block_id` into `words` (capacity `capacity`) and its length into `*count`.
/// Returns kUnknownBlock, or kWrongLength if the capacity is too small (nothing written).
ConstantsStatus ImuConstantsReadBlock(const ImuConstants* constants,
                                      uint8_t block_id,
                                      int16_t* words,
                                      uint8_t capacity,
                                      uint8_t* count);

}  // namespace adahrs::firmware_model
