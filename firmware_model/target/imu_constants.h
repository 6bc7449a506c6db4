// The IM3 unit's calibration constants in target (fixed-point) form, and the block-wise access the
// maintenance port uses to write and read them (reference-method.md, Chapter 2 steps 2-5).
// Channels 0 az1, 1 ax1, 2 ay1, 3 az2, 4 ax2, 5 ay2 (ADXL210E duty, two per body axis with opposite
// polarity), 6 gx, 7 gy, 8 gz (ADXRS150); temperature sensors 0..2 are the gyros' on-chip sensors.
// Stages: U raw, xi thermal cubic in the normalised temperature (Eq. 4-5 extended; held at its end
// value beyond the span), T = U - xi, Ca = (T - O)(1/S) (Eq. 12), Cg gyro cubic (Eq. 23),
// A = CA mean-pair(Ca) (Eq. 26), G = CG Cg (Eq. 29); format 3 (block 0x10 on) adds a scale factor
// F(tau_s) per channel, q Ca^2 per axis and GS A. Blocks 0x01..0x0F are the format-2 set, all
// needed before a commit; 0x10..0x1B are written all together or not at all. A write validates the
// whole block first and derives the Q15 run-time forms.
// Units: value = mantissa * 2^(exponent - 31) (fixed_coeff.h); duty, counts, g, m/s^2, deg/s.
// Channels, stage formats, the block table: docs/firmware-compensator.md ("Constants blocks",
// "Stages", "Scale-temperature stages").
// Not modelled: run-time bias estimation, and any constants version or CRC (the maintenance
// handler's).
#ifndef ADAHRS_FW_IMU_CONSTANTS_H
#define ADAHRS_FW_IMU_CONSTANTS_H

#include <stdint.h>

#include "fixed_coeff.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FW_ACCEL_CHANNELS 6u
#define FW_GYRO_CHANNELS 3u
#define FW_IMU_CHANNELS (FW_ACCEL_CHANNELS + FW_GYRO_CHANNELS)
#define FW_TEMP_SENSORS 3u

/// Exponents of the stage formats (value = mantissa * 2^(exponent - 31)).
#define FW_DUTY_EXPONENT 0          ///< duty, |U| < 1
#define FW_GYRO_COUNT_EXPONENT 23   ///< gyro counts, |U| < 2^23 (LSB 1/256 count)
#define FW_TEMP_COUNT_EXPONENT 31   ///< temperature counts, raw integer
#define FW_ACCEL_G_EXPONENT 4       ///< specific force in g, |Ca| < 16 g
#define FW_ACCEL_MPS2_EXPONENT 8    ///< specific force in m/s^2, |A| < 256 m/s^2
#define FW_RATE_EXPONENT 8          ///< angular rate in deg/s, |G| < 256 deg/s
#define FW_SCALE_FACTOR_EXPONENT 1  ///< dimensionless scale factor, |F| < 2

/// Rated input envelope used by the overflow check of the cross-axis matrices (Table 5).
#define FW_RATED_ACCEL_G 10
#define FW_RATED_RATE_DPS 150
#define FW_RATED_ACCEL_MPS2 99  ///< 10 g, rounded up

/// Degree of the thermal drift polynomial xi and of the scale factors F.
#define FW_IMU_THERMAL_DEGREE 3u
#define FW_IMU_SCALE_FACTOR_DEGREE 3u

typedef struct {
  uint8_t temp_sensor;       ///< 0..2: which temperature count drives this channel
  FwInputNormQ31 temp_norm;  ///< tau = (t_cnt - centre) * 2^-shift, shift <= 16
  FwPolyQ31 drift;           ///< xi(tau), degree FW_IMU_THERMAL_DEGREE, in the channel's U units
  /// drift's mantissas aligned to its working exponent (floor, as Horner's SFTAC does), derived on
  /// write (fw_derive_thermal_aligned): the format-3 path evaluates xi as a dot product on tau's
  /// powers.
  int32_t drift_aligned_q31[FW_IMU_THERMAL_DEGREE + 1u];
} FwThermalConstantsQ31;

typedef struct {
  int32_t offset_duty_q31;  ///< O, duty at exponent 0
  FwCoeffQ31 inv_scale_g;   ///< 1/S, g per duty unit
} FwAccelScaleConstantsQ31;

typedef struct {
  FwInputNormQ31 count_norm;  ///< x = (T - centre) * 2^-shift, centre at FW_GYRO_COUNT_EXPONENT
  FwPolyQ31 rate;             ///< Eq. 23 in x, deg/s, work_exponent == FW_RATE_EXPONENT
} FwGyroCubicConstantsQ31;

/// Run-time form of a scale factor, derived from its block on write: F = 1 + delta,
/// delta(tau) = d0 + d1 tau + d2 tau^2 + d3 tau^3 at `exponent`, d0 a Q31 mantissa there and the
/// tempco terms d1..d3 Q15 mantissas at the finer `tempco_exponent` (value = d 2^(e - 15)), with
/// |d0| + sum_k |d_k| below 2^exponent so no partial sum overflows for |tau| <= 1.
typedef struct {
  int32_t d0_q31;
  int16_t d_q15[FW_IMU_SCALE_FACTOR_DEGREE];  ///< d1..d3
  int8_t exponent;                            ///< -16..2
  int8_t tempco_exponent;                     ///< exponent - 16 .. exponent
} FwScaleDeltaQ15;

/// Run-time form of GS, derived from block 0x1B on write: Q15 mantissas at one exponent per row
/// (value = m 2^(row_exponent - 15)), each row's sum_j |m| <= 32767.
typedef struct {
  int16_t m_q15[3][3];
  int8_t row_exponent[3];  ///< -16..2
} FwGSensitivityQ15;

/// The format-3 stages (blocks 0x10..0x1B), and the Q15 forms the compensator runs, derived on
/// write (fw_derive_scale_temperature_q15).
typedef struct {
  uint8_t enabled;                            ///< 0: skipped (a format-2 set), 1: run
  FwInputNormQ31 temp_norm[FW_TEMP_SENSORS];  ///< tau_s, shift <= 16
  FwPolyQ31 scale[FW_IMU_CHANNELS];           ///< F_c(tau), work_exponent == FW_SCALE_FACTOR_..
  FwCoeffQ31 accel_quadratic[3];              ///< q per body axis, g per g^2
  FwCoeffQ31 gs[3][3];                        ///< GS, deg/s per m/s^2
  FwScaleDeltaQ15 delta[FW_IMU_CHANNELS];     ///< F_c - 1, derived from scale[c]
  int16_t accel_quadratic_q15[3];  ///< q rounded to Q15 at accel_quadratic[axis].exponent
  FwGSensitivityQ15 gs_q15;        ///< derived from gs
} FwScaleTemperatureConstantsQ31;

typedef struct {
  FwThermalConstantsQ31 thermal[FW_IMU_CHANNELS];
  FwAccelScaleConstantsQ31 accel[FW_ACCEL_CHANNELS];
  FwGyroCubicConstantsQ31 gyro[FW_GYRO_CHANNELS];
  FwCoeffQ31 ca[3][3];  ///< CA, A_mps2 = CA * Ca_g
  FwCoeffQ31 cg[3][3];  ///< CG, G_dps = CG * Cg_dps
  FwScaleTemperatureConstantsQ31 scale_temperature;
} FwImuConstants;

/// Block ids of the IMU constant set.
#define FW_IMU_BLOCK_THERMAL_FIRST 0x01u  ///< 0x01..0x09: thermal, channel = id - 0x01
#define FW_IMU_BLOCK_THERMAL_LAST 0x09u
#define FW_IMU_BLOCK_ACCEL_OFFSET_SCALE 0x0Au
#define FW_IMU_BLOCK_GYRO_CUBIC_FIRST 0x0Bu  ///< 0x0B..0x0D: gyro x, y, z
#define FW_IMU_BLOCK_GYRO_CUBIC_LAST 0x0Du
#define FW_IMU_BLOCK_CA 0x0Eu
#define FW_IMU_BLOCK_CG 0x0Fu
#define FW_IMU_BLOCK_SCALE_SWITCH 0x10u        ///< format-3 switch and temperature normalisations
#define FW_IMU_BLOCK_SCALE_FACTOR_FIRST 0x11u  ///< 0x11..0x19: F, channel = id - 0x11
#define FW_IMU_BLOCK_SCALE_FACTOR_LAST 0x19u
#define FW_IMU_BLOCK_ACCEL_QUADRATIC 0x1Au
#define FW_IMU_BLOCK_GS 0x1Bu
/// The format-2 set is 0x01..0x0F; the format-3 blocks are 0x10..FW_IMU_BLOCK_LAST.
#define FW_IMU_BLOCK_LAST FW_IMU_BLOCK_GS

#define FW_IMU_THERMAL_BLOCK_WORDS (1u + FW_NORM_WORDS + FW_POLY_WORDS(FW_IMU_THERMAL_DEGREE))
#define FW_IMU_ACCEL_BLOCK_WORDS (FW_ACCEL_CHANNELS * (2u + FW_COEFF_WORDS))
#define FW_IMU_GYRO_BLOCK_WORDS (FW_NORM_WORDS + FW_POLY_WORDS(3u))
#define FW_IMU_MATRIX_BLOCK_WORDS (9u * FW_COEFF_WORDS)
#define FW_IMU_SCALE_SWITCH_BLOCK_WORDS (1u + (FW_TEMP_SENSORS * FW_NORM_WORDS))
#define FW_IMU_SCALE_FACTOR_BLOCK_WORDS FW_POLY_WORDS(FW_IMU_SCALE_FACTOR_DEGREE)
#define FW_IMU_ACCEL_QUADRATIC_BLOCK_WORDS (3u * FW_COEFF_WORDS)
/// Longest IMU block, for callers sizing a buffer.
#define FW_IMU_MAX_BLOCK_WORDS FW_IMU_ACCEL_BLOCK_WORDS

/// The Q15 run-time forms of the format-3 blocks (FwScaleTemperatureConstantsQ31). A write of
/// block 0x11..0x1B derives them; a caller that fills the Q31 fields itself (the exporter) calls
/// fw_derive_scale_temperature_q15 afterwards. Rounding: to nearest, |error| <= 1/2 LSB of each
/// mantissa.
void fw_derive_thermal_aligned(FwThermalConstantsQ31* thermal);
void fw_derive_scale_delta(const FwPolyQ31* scale, FwScaleDeltaQ15* delta);
int16_t fw_derive_q15(const FwCoeffQ31* coeff);
void fw_derive_scale_temperature_q15(FwScaleTemperatureConstantsQ31* st);

/// Puts the set into its uncalibrated state: zero drift, zero offsets, zero scales, zero gyro
/// polynomials, identity matrices (so every calibrated output of an unconfigured unit reads zero),
/// and the format-3 stages off (scale factors 1, q and GS zero).
void fw_imu_constants_init(FwImuConstants* constants);

/// Words in block `block_id`, or 0 if the block is unknown.
uint8_t fw_imu_constants_block_length(uint8_t block_id);

/// Replaces block `block_id` from `count` words. Returns OK, or the first reason for refusal; on
/// refusal `constants` is unchanged.
FwConstantsStatus fw_imu_constants_write_block(FwImuConstants* constants,
                                               uint8_t block_id,
                                               const int16_t* words,
                                               uint8_t count);

/// Writes block `block_id` into `words` (capacity `capacity`) and its length into `*count`.
/// Returns UNKNOWN_BLOCK, or WRONG_LENGTH if the capacity is too small (nothing written).
FwConstantsStatus fw_imu_constants_read_block(const FwImuConstants* constants,
                                              uint8_t block_id,
                                              int16_t* words,
                                              uint8_t capacity,
                                              uint8_t* count);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_IMU_CONSTANTS_H
