#include "imu_constants.h"

#include <stdbool.h>
#include <stddef.h>

#include "q_math.h"

// Exponent range of the Q15 run-time forms (FwScaleDeltaQ15, FwGSensitivityQ15).
#define MIN_Q15_EXPONENT (-16)
#define MAX_Q15_EXPONENT 2

static FwCoeffQ31 MakeCoeff(int32_t mantissa_q31, int8_t exponent) {
  FwCoeffQ31 c;
  c.mantissa_q31 = mantissa_q31;
  c.exponent = exponent;
  return c;
}

static FwInputNormQ31 MakeNorm(int32_t centre, uint8_t shift) {
  FwInputNormQ31 n;
  n.centre = centre;
  n.shift = shift;
  return n;
}

// 1.0 at exponent 1: mantissa 2^30.
static FwCoeffQ31 OneCoeff(void) { return MakeCoeff(INT32_C(0x40000000), 1); }

static int64_t AbsMantissa(int32_t m) { return (m < 0) ? -(int64_t)m : (int64_t)m; }

static void ZeroPoly(FwPolyQ31* poly, int8_t work_exponent) {
  poly->work_exponent = work_exponent;
  for (uint8_t k = 0u; k <= FW_MAX_POLY_DEGREE; ++k) {
    poly->coeff[k] = MakeCoeff(0, work_exponent);
  }
}

static void IdentityMatrix(FwCoeffQ31 m[3][3]) {
  for (uint8_t r = 0u; r < 3u; ++r) {
    for (uint8_t c = 0u; c < 3u; ++c) {
      m[r][c] = (r == c) ? OneCoeff() : MakeCoeff(0, 0);
    }
  }
}

// A row sum of |C| times the rated input must stay below the output full scale 2^out_exponent:
// sum_j |m_j| 2^(e_j - 31) * rated < 2^out_exponent. Exponents are validated to -40..40 first.
static FwConstantsStatus ValidateMatrixRow(const FwCoeffQ31* row,
                                           int32_t rated,
                                           int8_t out_exponent) {
  // Accumulate |m| * rated * 2^(e - out_exponent + 16) in Q31 units scaled by 2^16.
  int64_t sum = 0;
  for (uint8_t c = 0u; c < 3u; ++c) {
    const int16_t e = row[c].exponent;
    const int16_t shift = (int16_t)((e - (int16_t)out_exponent) + 16);
    if ((e < FW_MIN_EXPONENT) || (e > FW_MAX_EXPONENT) || (shift < 0) || (shift > 20)) {
      return FW_CONSTANTS_OUT_OF_RANGE;
    }
    sum += (AbsMantissa(row[c].mantissa_q31) * (int64_t)rated) * (INT64_C(1) << (uint8_t)shift);
  }
  return (sum >= (INT64_C(1) << (31 + 16))) ? FW_CONSTANTS_WOULD_OVERFLOW : FW_CONSTANTS_OK;
}

static FwConstantsStatus MatrixFromWords(const int16_t* words,
                                         int32_t rated,
                                         int8_t out_exponent,
                                         FwCoeffQ31 out[3][3]) {
  FwCoeffQ31 decoded[3][3];
  for (uint8_t k = 0u; k < 9u; ++k) {
    const FwConstantsStatus s =
        fw_coeff_from_words(&words[FW_COEFF_WORDS * k], &decoded[k / 3u][k % 3u]);
    if (s != FW_CONSTANTS_OK) {
      return s;
    }
  }
  for (uint8_t r = 0u; r < 3u; ++r) {
    const FwConstantsStatus s = ValidateMatrixRow(decoded[r], rated, out_exponent);
    if (s != FW_CONSTANTS_OK) {
      return s;
    }
  }
  for (uint8_t k = 0u; k < 9u; ++k) {
    out[k / 3u][k % 3u] = decoded[k / 3u][k % 3u];
  }
  return FW_CONSTANTS_OK;
}

static void MatrixToWords(const FwCoeffQ31 m[3][3], int16_t* words) {
  for (uint8_t k = 0u; k < 9u; ++k) {
    fw_coeff_to_words(&m[k / 3u][k % 3u], &words[FW_COEFF_WORDS * k]);
  }
}

static FwConstantsStatus ThermalFromWords(const int16_t* words,
                                          uint8_t channel,
                                          FwThermalConstantsQ31* out) {
  if ((words[0] < 0) || (words[0] >= (int16_t)FW_TEMP_SENSORS)) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  FwThermalConstantsQ31 decoded = {0};
  decoded.temp_sensor = (uint8_t)words[0];
  FwConstantsStatus s = fw_norm_from_words(&words[1], 16u, &decoded.temp_norm);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  s = fw_poly_from_words(&words[1u + FW_NORM_WORDS], FW_IMU_THERMAL_DEGREE, &decoded.drift);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  // xi is subtracted from U at U's exponent; it may be evaluated at most 16 bits finer or coarser.
  const int8_t u_exponent =
      (channel < FW_ACCEL_CHANNELS) ? (int8_t)FW_DUTY_EXPONENT : (int8_t)FW_GYRO_COUNT_EXPONENT;
  const int16_t bring = (int16_t)((int16_t)decoded.drift.work_exponent - (int16_t)u_exponent);
  if ((bring < -FW_MAX_ALIGN_SHIFT) || (bring > FW_MAX_ALIGN_SHIFT)) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  fw_derive_thermal_aligned(&decoded);
  *out = decoded;
  return FW_CONSTANTS_OK;
}

static FwConstantsStatus AccelFromWords(const int16_t* words,
                                        FwAccelScaleConstantsQ31 out[FW_ACCEL_CHANNELS]) {
  FwAccelScaleConstantsQ31 decoded[FW_ACCEL_CHANNELS] = {0};
  for (uint8_t c = 0u; c < FW_ACCEL_CHANNELS; ++c) {
    const int16_t* w = &words[c * (2u + FW_COEFF_WORDS)];
    decoded[c].offset_duty_q31 = fw_join32(w[0], w[1]);
    const FwConstantsStatus s = fw_coeff_from_words(&w[2], &decoded[c].inv_scale_g);
    if (s != FW_CONSTANTS_OK) {
      return s;
    }
    // (T - O) is a duty at exponent 0; the product (T - O) * (1/S) is at exponent e and is brought
    // to the g format by one SFTAC of (FW_ACCEL_G_EXPONENT - e) bits.
    const int16_t e = decoded[c].inv_scale_g.exponent;
    const int16_t bring = (int16_t)(e - FW_ACCEL_G_EXPONENT);  // FW_DUTY_EXPONENT is 0
    if ((bring < -FW_MAX_ALIGN_SHIFT) || (bring > FW_MAX_ALIGN_SHIFT)) {
      return FW_CONSTANTS_OUT_OF_RANGE;
    }
    // Rated duty span: |T - O| <= 0.5 duty, so |1/S| * 0.5 < 16 g, i.e. |1/S| < 32 g per duty.
    // |1/S| = abs_m * 2^(e - 31) < 32  <=>  abs_m * 2^e < 2^36 (e <= 36 here is implied by bring).
    const int64_t abs_m = AbsMantissa(decoded[c].inv_scale_g.mantissa_q31);
    const int16_t threshold_log2 = (int16_t)(36 - e);
    const bool too_large = (e >= 0) ? ((abs_m * (INT64_C(1) << (uint8_t)e)) >= (INT64_C(1) << 36))
                                    : (abs_m >= (INT64_C(1) << (uint8_t)threshold_log2));
    if (too_large) {
      return FW_CONSTANTS_WOULD_OVERFLOW;
    }
  }
  for (uint8_t c = 0u; c < FW_ACCEL_CHANNELS; ++c) {
    out[c] = decoded[c];
  }
  return FW_CONSTANTS_OK;
}

static FwConstantsStatus GyroFromWords(const int16_t* words, FwGyroCubicConstantsQ31* out) {
  FwGyroCubicConstantsQ31 decoded = {0};
  FwConstantsStatus s =
      fw_norm_from_words(words, (uint8_t)FW_GYRO_COUNT_EXPONENT, &decoded.count_norm);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  s = fw_poly_from_words(&words[FW_NORM_WORDS], 3u, &decoded.rate);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  if (decoded.rate.work_exponent != FW_RATE_EXPONENT) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  *out = decoded;
  return FW_CONSTANTS_OK;
}

// [enabled][3 x norm]: enabled must be 0 or 1, every shift <= 16.
static FwConstantsStatus ScaleSwitchFromWords(const int16_t* words,
                                              FwScaleTemperatureConstantsQ31* out) {
  if ((words[0] != 0) && (words[0] != 1)) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  FwInputNormQ31 norms[FW_TEMP_SENSORS];
  for (uint8_t s = 0u; s < FW_TEMP_SENSORS; ++s) {
    const FwConstantsStatus status =
        fw_norm_from_words(&words[1u + (s * FW_NORM_WORDS)], 16u, &norms[s]);
    if (status != FW_CONSTANTS_OK) {
      return status;
    }
  }
  out->enabled = (uint8_t)words[0];
  for (uint8_t s = 0u; s < FW_TEMP_SENSORS; ++s) {
    out->temp_norm[s] = norms[s];
  }
  return FW_CONSTANTS_OK;
}

static FwConstantsStatus ScaleFactorFromWords(const int16_t* words, FwPolyQ31* out) {
  FwPolyQ31 decoded = {0};
  const FwConstantsStatus s = fw_poly_from_words(words, FW_IMU_SCALE_FACTOR_DEGREE, &decoded);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  if (decoded.work_exponent != FW_SCALE_FACTOR_EXPONENT) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  *out = decoded;
  return FW_CONSTANTS_OK;
}

// q per axis: q ca^2 is formed as (ca^2 at 2 FW_ACCEL_G_EXPONENT) * q, brought to
// FW_ACCEL_G_EXPONENT by one SFTAC of (FW_ACCEL_G_EXPONENT - 2 FW_ACCEL_G_EXPONENT - e) bits, which
// must lie in -16..16; and |q| * (16 g)^2 < 16 g keeps the term inside the g format for any ca the
// stage can hold.
static FwConstantsStatus AccelQuadraticFromWords(const int16_t* words, FwCoeffQ31 out[3]) {
  FwCoeffQ31 decoded[3];
  for (uint8_t axis = 0u; axis < 3u; ++axis) {
    const FwConstantsStatus s = fw_coeff_from_words(&words[axis * FW_COEFF_WORDS], &decoded[axis]);
    if (s != FW_CONSTANTS_OK) {
      return s;
    }
    const int16_t shift = (int16_t)(-FW_ACCEL_G_EXPONENT - decoded[axis].exponent);
    if ((shift < -FW_MAX_ALIGN_SHIFT) || (shift > FW_MAX_ALIGN_SHIFT)) {
      return FW_CONSTANTS_OUT_OF_RANGE;
    }
    // |q| < 1/16 g per g^2  <=>  |m| 2^(e - 31) < 2^-4  <=>  |m| < 2^(27 - e).
    const int64_t abs_m = AbsMantissa(decoded[axis].mantissa_q31);
    const int16_t limit_log2 = (int16_t)(27 - decoded[axis].exponent);
    if ((limit_log2 <= 31) && (abs_m >= (INT64_C(1) << (uint8_t)limit_log2))) {
      return FW_CONSTANTS_WOULD_OVERFLOW;
    }
  }
  for (uint8_t axis = 0u; axis < 3u; ++axis) {
    out[axis] = decoded[axis];
  }
  return FW_CONSTANTS_OK;
}

// value * 2^47 of a coefficient with exponent <= 16 (exact for exponent >= -16, floor below).
static int64_t Units47(const FwCoeffQ31* c) {
  const int16_t shift = (int16_t)(c->exponent + 16);
  return (shift >= 0) ? ((int64_t)c->mantissa_q31 * (INT64_C(1) << (uint8_t)shift))
                      : fw_asr64((int64_t)c->mantissa_q31, (uint8_t)(-shift));
}

// units47 / 2^shift rounded to nearest (halves up). A value held as value 2^47 has the Q31
// mantissa RoundShift(units47, 16 + e) and the Q15 mantissa RoundShift(units47, 32 + e) at
// exponent e.
static int64_t RoundShift(int64_t units47, int16_t shift) {
  const int16_t half_log2 = (int16_t)(shift - 1);
  return (shift <= 0) ? units47
                      : fw_asr64(units47 + (INT64_C(1) << (uint8_t)half_log2), (uint8_t)shift);
}

static int16_t SatInt16(int64_t v) {
  return (v > INT16_MAX) ? (int16_t)INT16_MAX : ((v < INT16_MIN) ? (int16_t)INT16_MIN : (int16_t)v);
}

// Sum of |Q15 mantissas| of `count` values at `exponent`.
static int64_t SumAbsQ15(const int64_t* units47, uint8_t count, int16_t exponent) {
  int64_t sum_abs = 0;
  for (uint8_t k = 0u; k < count; ++k) {
    const int64_t m = RoundShift(units47[k], (int16_t)(32 + (int16_t)exponent));
    sum_abs += (m < 0) ? -m : m;
  }
  return sum_abs;
}

// Q15 mantissas at the smallest exponent, from `min_exponent` to MAX_Q15_EXPONENT, whose rounded
// mantissas sum to at most 32767 in magnitude; returns that exponent.
static int8_t BlockQ15(const int64_t* units47, uint8_t count, int8_t min_exponent, int16_t* m_q15) {
  int8_t exponent = min_exponent;
  while ((exponent < MAX_Q15_EXPONENT) && (SumAbsQ15(units47, count, exponent) > INT16_MAX)) {
    ++exponent;
  }
  for (uint8_t k = 0u; k < count; ++k) {
    m_q15[k] = SatInt16(RoundShift(units47[k], (int16_t)(32 + (int16_t)exponent)));
  }
  return exponent;
}

static void DeriveGSensitivity(FwScaleTemperatureConstantsQ31* st) {
  for (uint8_t r = 0u; r < 3u; ++r) {
    int64_t units47[3];
    for (uint8_t c = 0u; c < 3u; ++c) {
      units47[c] = Units47(&st->gs[r][c]);
    }
    st->gs_q15.row_exponent[r] = BlockQ15(units47, 3u, MIN_Q15_EXPONENT, st->gs_q15.m_q15[r]);
  }
}

static void ScaleTemperatureInit(FwScaleTemperatureConstantsQ31* st) {
  st->enabled = 0u;
  for (uint8_t s = 0u; s < FW_TEMP_SENSORS; ++s) {
    st->temp_norm[s] = MakeNorm(INT32_C(32768), 16u);
  }
  for (uint8_t c = 0u; c < FW_IMU_CHANNELS; ++c) {
    ZeroPoly(&st->scale[c], FW_SCALE_FACTOR_EXPONENT);
    st->scale[c].coeff[0] = OneCoeff();
  }
  for (uint8_t axis = 0u; axis < 3u; ++axis) {
    st->accel_quadratic[axis] = MakeCoeff(0, 0);
  }
  for (uint8_t r = 0u; r < 3u; ++r) {
    for (uint8_t c = 0u; c < 3u; ++c) {
      st->gs[r][c] = MakeCoeff(0, 0);
    }
  }
  fw_derive_scale_temperature_q15(st);
}

static FwConstantsStatus ScaleTemperatureWriteBlock(FwScaleTemperatureConstantsQ31* st,
                                                    uint8_t block_id,
                                                    const int16_t* words) {
  if (block_id == FW_IMU_BLOCK_SCALE_SWITCH) {
    return ScaleSwitchFromWords(words, st);
  }
  FwConstantsStatus s = FW_CONSTANTS_OK;
  if (block_id <= FW_IMU_BLOCK_SCALE_FACTOR_LAST) {
    s = ScaleFactorFromWords(words, &st->scale[block_id - FW_IMU_BLOCK_SCALE_FACTOR_FIRST]);
  } else if (block_id == FW_IMU_BLOCK_ACCEL_QUADRATIC) {
    s = AccelQuadraticFromWords(words, st->accel_quadratic);
  } else {
    s = MatrixFromWords(words, FW_RATED_ACCEL_MPS2, FW_RATE_EXPONENT, st->gs);
  }
  if (s == FW_CONSTANTS_OK) {
    fw_derive_scale_temperature_q15(st);
  }
  return s;
}

static void ScaleTemperatureReadBlock(const FwScaleTemperatureConstantsQ31* st,
                                      uint8_t block_id,
                                      int16_t* words) {
  if (block_id == FW_IMU_BLOCK_SCALE_SWITCH) {
    words[0] = (int16_t)st->enabled;
    for (uint8_t s = 0u; s < FW_TEMP_SENSORS; ++s) {
      fw_norm_to_words(&st->temp_norm[s], &words[1u + (s * FW_NORM_WORDS)]);
    }
  } else if (block_id <= FW_IMU_BLOCK_SCALE_FACTOR_LAST) {
    fw_poly_to_words(
        &st->scale[block_id - FW_IMU_BLOCK_SCALE_FACTOR_FIRST], FW_IMU_SCALE_FACTOR_DEGREE, words);
  } else if (block_id == FW_IMU_BLOCK_ACCEL_QUADRATIC) {
    for (uint8_t axis = 0u; axis < 3u; ++axis) {
      fw_coeff_to_words(&st->accel_quadratic[axis], &words[axis * FW_COEFF_WORDS]);
    }
  } else {
    MatrixToWords(st->gs, words);
  }
}

void fw_derive_thermal_aligned(FwThermalConstantsQ31* thermal) {
  for (uint8_t k = 0u; k <= FW_IMU_THERMAL_DEGREE; ++k) {
    const FwCoeffQ31* c = &thermal->drift.coeff[k];
    const int16_t align = (int16_t)((int16_t)thermal->drift.work_exponent - (int16_t)c->exponent);
    thermal->drift_aligned_q31[k] = (int32_t)fw_asr64((int64_t)c->mantissa_q31, (uint8_t)align);
  }
}

void fw_derive_scale_delta(const FwPolyQ31* scale, FwScaleDeltaQ15* delta) {
  int64_t units47[FW_IMU_SCALE_FACTOR_DEGREE + 1u];
  for (uint8_t k = 0u; k <= FW_IMU_SCALE_FACTOR_DEGREE; ++k) {
    units47[k] = Units47(&scale->coeff[k]);
  }
  units47[0] -= INT64_C(1) << 47;  // delta = F - 1
  // delta's exponent: the smallest whose Q31 holds |d0| + sum_k |d_k| with a margin of 4 2^16
  // LSB, which covers d1..d3 rounded to Q15 at an exponent no coarser (2^15 LSB each at most).
  int64_t sum_abs47 = 0;
  for (uint8_t k = 0u; k <= FW_IMU_SCALE_FACTOR_DEGREE; ++k) {
    sum_abs47 += (units47[k] < 0) ? -units47[k] : units47[k];
  }
  int8_t exponent = MIN_Q15_EXPONENT;
  while ((exponent < MAX_Q15_EXPONENT) &&
         ((RoundShift(sum_abs47, (int16_t)(16 + (int16_t)exponent)) + (4 * (INT64_C(1) << 16))) >
          INT32_MAX)) {
    ++exponent;
  }
  const int8_t lowest = (int8_t)(exponent - 16);
  delta->tempco_exponent = BlockQ15(&units47[1],
                                    FW_IMU_SCALE_FACTOR_DEGREE,
                                    (lowest < MIN_Q15_EXPONENT) ? (int8_t)MIN_Q15_EXPONENT : lowest,
                                    delta->d_q15);
  if (delta->tempco_exponent > exponent) {
    exponent = delta->tempco_exponent;
  }
  delta->exponent = exponent;
  delta->d0_q31 = (int32_t)RoundShift(units47[0], (int16_t)(16 + (int16_t)exponent));
}

int16_t fw_derive_q15(const FwCoeffQ31* coeff) {
  const int64_t m = fw_asr64((int64_t)coeff->mantissa_q31 + (INT64_C(1) << 15), 16u);
  return (m > INT16_MAX) ? (int16_t)INT16_MAX : (int16_t)m;
}

void fw_derive_scale_temperature_q15(FwScaleTemperatureConstantsQ31* st) {
  for (uint8_t c = 0u; c < FW_IMU_CHANNELS; ++c) {
    fw_derive_scale_delta(&st->scale[c], &st->delta[c]);
  }
  for (uint8_t axis = 0u; axis < 3u; ++axis) {
    st->accel_quadratic_q15[axis] = fw_derive_q15(&st->accel_quadratic[axis]);
  }
  DeriveGSensitivity(st);
}

void fw_imu_constants_init(FwImuConstants* constants) {
  for (uint8_t c = 0u; c < FW_IMU_CHANNELS; ++c) {
    FwThermalConstantsQ31* t = &constants->thermal[c];
    if (c < FW_ACCEL_CHANNELS) {
      t->temp_sensor = (uint8_t)(c % FW_TEMP_SENSORS);
    } else {
      t->temp_sensor = (uint8_t)(c - FW_ACCEL_CHANNELS);
    }
    t->temp_norm = MakeNorm(INT32_C(32768), 16u);
    ZeroPoly(&t->drift,
             (c < FW_ACCEL_CHANNELS) ? (int8_t)FW_DUTY_EXPONENT : (int8_t)FW_GYRO_COUNT_EXPONENT);
    fw_derive_thermal_aligned(t);
  }
  for (uint8_t c = 0u; c < FW_ACCEL_CHANNELS; ++c) {
    constants->accel[c].offset_duty_q31 = 0;
    constants->accel[c].inv_scale_g = MakeCoeff(0, 5);
  }
  for (uint8_t g = 0u; g < FW_GYRO_CHANNELS; ++g) {
    constants->gyro[g].count_norm = MakeNorm(0, (uint8_t)FW_GYRO_COUNT_EXPONENT);
    ZeroPoly(&constants->gyro[g].rate, FW_RATE_EXPONENT);
  }
  IdentityMatrix(constants->ca);
  IdentityMatrix(constants->cg);
  ScaleTemperatureInit(&constants->scale_temperature);
}

uint8_t fw_imu_constants_block_length(uint8_t block_id) {
  uint8_t length = 0u;
  if ((block_id >= FW_IMU_BLOCK_THERMAL_FIRST) && (block_id <= FW_IMU_BLOCK_THERMAL_LAST)) {
    length = FW_IMU_THERMAL_BLOCK_WORDS;
  } else if (block_id == FW_IMU_BLOCK_ACCEL_OFFSET_SCALE) {
    length = FW_IMU_ACCEL_BLOCK_WORDS;
  } else if ((block_id >= FW_IMU_BLOCK_GYRO_CUBIC_FIRST) &&
             (block_id <= FW_IMU_BLOCK_GYRO_CUBIC_LAST)) {
    length = FW_IMU_GYRO_BLOCK_WORDS;
  } else if ((block_id == FW_IMU_BLOCK_CA) || (block_id == FW_IMU_BLOCK_CG)) {
    length = FW_IMU_MATRIX_BLOCK_WORDS;
  } else if (block_id == FW_IMU_BLOCK_SCALE_SWITCH) {
    length = FW_IMU_SCALE_SWITCH_BLOCK_WORDS;
  } else if ((block_id >= FW_IMU_BLOCK_SCALE_FACTOR_FIRST) &&
             (block_id <= FW_IMU_BLOCK_SCALE_FACTOR_LAST)) {
    length = FW_IMU_SCALE_FACTOR_BLOCK_WORDS;
  } else if (block_id == FW_IMU_BLOCK_ACCEL_QUADRATIC) {
    length = FW_IMU_ACCEL_QUADRATIC_BLOCK_WORDS;
  } else if (block_id == FW_IMU_BLOCK_GS) {
    length = FW_IMU_MATRIX_BLOCK_WORDS;
  } else {
    // unknown: 0
  }
  return length;
}

FwConstantsStatus fw_imu_constants_write_block(FwImuConstants* constants,
                                               uint8_t block_id,
                                               const int16_t* words,
                                               uint8_t count) {
  if ((constants == NULL) || (words == NULL)) {
    return FW_CONSTANTS_NULL_ARGUMENT;
  }
  const uint8_t length = fw_imu_constants_block_length(block_id);
  if (length == 0u) {
    return FW_CONSTANTS_UNKNOWN_BLOCK;
  }
  if (count != length) {
    return FW_CONSTANTS_WRONG_LENGTH;
  }
  FwConstantsStatus status = FW_CONSTANTS_OK;
  if (block_id <= FW_IMU_BLOCK_THERMAL_LAST) {
    const uint8_t channel = (uint8_t)(block_id - FW_IMU_BLOCK_THERMAL_FIRST);
    status = ThermalFromWords(words, channel, &constants->thermal[channel]);
  } else if (block_id == FW_IMU_BLOCK_ACCEL_OFFSET_SCALE) {
    status = AccelFromWords(words, constants->accel);
  } else if (block_id <= FW_IMU_BLOCK_GYRO_CUBIC_LAST) {
    status = GyroFromWords(words, &constants->gyro[block_id - FW_IMU_BLOCK_GYRO_CUBIC_FIRST]);
  } else if (block_id == FW_IMU_BLOCK_CA) {
    status = MatrixFromWords(words, FW_RATED_ACCEL_G, FW_ACCEL_MPS2_EXPONENT, constants->ca);
  } else if (block_id == FW_IMU_BLOCK_CG) {
    status = MatrixFromWords(words, FW_RATED_RATE_DPS, FW_RATE_EXPONENT, constants->cg);
  } else {
    status = ScaleTemperatureWriteBlock(&constants->scale_temperature, block_id, words);
  }
  return status;
}

FwConstantsStatus fw_imu_constants_read_block(const FwImuConstants* constants,
                                              uint8_t block_id,
                                              int16_t* words,
                                              uint8_t capacity,
                                              uint8_t* count) {
  if ((constants == NULL) || (words == NULL) || (count == NULL)) {
    return FW_CONSTANTS_NULL_ARGUMENT;
  }
  const uint8_t length = fw_imu_constants_block_length(block_id);
  if (length == 0u) {
    return FW_CONSTANTS_UNKNOWN_BLOCK;
  }
  if (capacity < length) {
    return FW_CONSTANTS_WRONG_LENGTH;
  }
  if (block_id <= FW_IMU_BLOCK_THERMAL_LAST) {
    const FwThermalConstantsQ31* t = &constants->thermal[block_id - FW_IMU_BLOCK_THERMAL_FIRST];
    words[0] = (int16_t)t->temp_sensor;
    fw_norm_to_words(&t->temp_norm, &words[1]);
    fw_poly_to_words(&t->drift, FW_IMU_THERMAL_DEGREE, &words[1u + FW_NORM_WORDS]);
  } else if (block_id == FW_IMU_BLOCK_ACCEL_OFFSET_SCALE) {
    for (uint8_t c = 0u; c < FW_ACCEL_CHANNELS; ++c) {
      int16_t* w = &words[c * (2u + FW_COEFF_WORDS)];
      w[0] = fw_high16(constants->accel[c].offset_duty_q31);
      w[1] = fw_low16(constants->accel[c].offset_duty_q31);
      fw_coeff_to_words(&constants->accel[c].inv_scale_g, &w[2]);
    }
  } else if (block_id <= FW_IMU_BLOCK_GYRO_CUBIC_LAST) {
    const FwGyroCubicConstantsQ31* g = &constants->gyro[block_id - FW_IMU_BLOCK_GYRO_CUBIC_FIRST];
    fw_norm_to_words(&g->count_norm, words);
    fw_poly_to_words(&g->rate, 3u, &words[FW_NORM_WORDS]);
  } else if (block_id <= FW_IMU_BLOCK_CG) {
    MatrixToWords((block_id == FW_IMU_BLOCK_CA) ? constants->ca : constants->cg, words);
  } else {
    ScaleTemperatureReadBlock(&constants->scale_temperature, block_id, words);
  }
  *count = length;
  return FW_CONSTANTS_OK;
}
