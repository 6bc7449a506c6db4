#include "firmware_model/target/imu_constants.h"

namespace adahrs::firmware_model {
namespace {

constexpr CoeffQ31 kZeroCoeff{0, 0};
// 1.0 at exponent 1: mantissa 2^30.
constexpr CoeffQ31 kOneCoeff{INT32_C(0x40000000), 1};

void ZeroPoly(PolyQ31* poly, int8_t work_exponent) {
  poly->work_exponent = work_exponent;
  for (CoeffQ31& c : poly->coeff) c = CoeffQ31{0, work_exponent};
}

void IdentityMatrix(CoeffQ31 m[3][3]) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m[r][c] = (r == c) ? kOneCoeff : kZeroCoeff;
  }
}

// Row sums of |C| times the rated input must stay below the output full scale 2^out_exponent:
// sum_j |m_j| 2^(e_j - 31) * rated < 2^out_exponent. Exponents are validated to -40..40 first.
ConstantsStatus ValidateMatrix(const CoeffQ31 m[3][3], int32_t rated, int8_t out_exponent) {
  for (int r = 0; r < 3; ++r) {
    // Accumulate |m| * rated * 2^(e - out_exponent + 16) in Q31 units scaled by 2^16.
    int64_t sum = 0;
    for (int c = 0; c < 3; ++c) {
      const int32_t e = m[r][c].exponent;
      const int32_t shift = e - out_exponent + 16;
      if (e < kMinExponent || e > kMaxExponent || shift < 0 || shift > 20) {
        return ConstantsStatus::kOutOfRange;
      }
      const int64_t abs_m = m[r][c].mantissa_q31 < 0 ? -static_cast<int64_t>(m[r][c].mantissa_q31)
                                                     : m[r][c].mantissa_q31;
      sum += (abs_m * rated) << shift;
    }
    if (sum >= (static_cast<int64_t>(1) << (31 + 16))) return ConstantsStatus::kWouldOverflow;
  }
  return ConstantsStatus::kOk;
}

ConstantsStatus MatrixFromWords(const int16_t* words,
                                int32_t rated,
                                int8_t out_exponent,
                                CoeffQ31 out[3][3]) {
  CoeffQ31 decoded[3][3];
  for (int k = 0; k < 9; ++k) {
    const ConstantsStatus s = CoeffFromWords(words + kCoeffWords * k, &decoded[k / 3][k % 3]);
    if (s != ConstantsStatus::kOk) return s;
  }
  const ConstantsStatus s = ValidateMatrix(decoded, rated, out_exponent);
  if (s != ConstantsStatus::kOk) return s;
  for (int k = 0; k < 9; ++k) out[k / 3][k % 3] = decoded[k / 3][k % 3];
  return ConstantsStatus::kOk;
}

void MatrixToWords(const CoeffQ31 m[3][3], int16_t* words) {
  for (int k = 0; k < 9; ++k) CoeffToWords(m[k / 3][k % 3], words + kCoeffWords * k);
}

ConstantsStatus ThermalFromWords(const int16_t* words, uint8_t channel, ThermalConstantsQ31* out) {
  if (words[0] < 0 || words[0] >= kTempSensors) return ConstantsStatus::kOutOfRange;
  ThermalConstantsQ31 decoded{};
  decoded.temp_sensor = static_cast<uint8_t>(words[0]);
  ConstantsStatus s = NormFromWords(words + 1, 16, &decoded.temp_norm);
  if (s != ConstantsStatus::kOk) return s;
  s = PolyFromWords(words + 1 + kNormWords, kImuThermalDegree, &decoded.drift);
  if (s != ConstantsStatus::kOk) return s;
  // xi is subtracted from U at U's exponent; it may be evaluated at most 16 bits finer or coarser.
  const int8_t u_exponent = channel < kAccelChannels ? kDutyExponent : kGyroCountExponent;
  const int32_t bring = decoded.drift.work_exponent - u_exponent;
  if (bring < -kMaxAlignShift || bring > kMaxAlignShift) return ConstantsStatus::kOutOfRange;
  DeriveThermalAligned(&decoded);
  *out = decoded;
  return ConstantsStatus::kOk;
}

ConstantsStatus AccelFromWords(const int16_t* words, AccelScaleConstantsQ31 out[kAccelChannels]) {
  AccelScaleConstantsQ31 decoded[kAccelChannels];
  for (uint8_t c = 0; c < kAccelChannels; ++c) {
    const int16_t* w = words + c * (2 + kCoeffWords);
    const uint32_t bits = (static_cast<uint32_t>(static_cast<uint16_t>(w[0])) << 16) |
                          static_cast<uint32_t>(static_cast<uint16_t>(w[1]));
    decoded[c].offset_duty_q31 = static_cast<int32_t>(bits);
    const ConstantsStatus s = CoeffFromWords(w + 2, &decoded[c].inv_scale_g);
    if (s != ConstantsStatus::kOk) return s;
    // (T - O) is a duty at exponent 0; the product (T - O) * (1/S) is at exponent e and is brought
    // to the g format by one SFTAC of (kAccelGExponent - e) bits.
    const int32_t bring = decoded[c].inv_scale_g.exponent + kDutyExponent - kAccelGExponent;
    if (bring < -kMaxAlignShift || bring > kMaxAlignShift) return ConstantsStatus::kOutOfRange;
    // Rated duty span: |T - O| <= 0.5 duty, so |1/S| * 0.5 < 16 g, i.e. |1/S| < 32 g per duty.
    const int64_t abs_m = decoded[c].inv_scale_g.mantissa_q31 < 0
                              ? -static_cast<int64_t>(decoded[c].inv_scale_g.mantissa_q31)
                              : decoded[c].inv_scale_g.mantissa_q31;
    const int32_t e = decoded[c].inv_scale_g.exponent;
    // |1/S| = abs_m * 2^(e - 31) < 32  <=>  abs_m * 2^e < 2^36 (e <= 36 here is implied by bring).
    if (e >= 0 ? (abs_m << e) >= (static_cast<int64_t>(1) << 36)
               : abs_m >= (static_cast<int64_t>(1) << (36 - e))) {
      return ConstantsStatus::kWouldOverflow;
    }
  }
  for (uint8_t c = 0; c < kAccelChannels; ++c) out[c] = decoded[c];
  return ConstantsStatus::kOk;
}

ConstantsStatus GyroFromWords(const int16_t* words, GyroCubicConstantsQ31* out) {
  GyroCubicConstantsQ31 decoded{};
  ConstantsStatus s = NormFromWords(words, kGyroCountExponent, &decoded.count_norm);
  if (s != ConstantsStatus::kOk) return s;
  s = PolyFromWords(words + kNormWords, 3, &decoded.rate);
  if (s != ConstantsStatus::kOk) return s;
  if (decoded.rate.work_exponent != kRateExponent) return ConstantsStatus::kOutOfRange;
  *out = decoded;
  return ConstantsStatus::kOk;
}

// [enabled][3 x norm]: enabled must be 0 or 1, every shift <= 16.
ConstantsStatus ScaleSwitchFromWords(const int16_t* words, ScaleTemperatureConstantsQ31* out) {
  if (words[0] != 0 && words[0] != 1) return ConstantsStatus::kOutOfRange;
  InputNormQ31 norms[kTempSensors];
  for (uint8_t s = 0; s < kTempSensors; ++s) {
    const ConstantsStatus status = NormFromWords(words + 1 + s * kNormWords, 16, &norms[s]);
    if (status != ConstantsStatus::kOk) return status;
  }
  out->enabled = static_cast<uint8_t>(words[0]);
  for (uint8_t s = 0; s < kTempSensors; ++s) out->temp_norm[s] = norms[s];
  return ConstantsStatus::kOk;
}

ConstantsStatus ScaleFactorFromWords(const int16_t* words, PolyQ31* out) {
  PolyQ31 decoded{};
  const ConstantsStatus s = PolyFromWords(words, kImuScaleFactorDegree, &decoded);
  if (s != ConstantsStatus::kOk) return s;
  if (decoded.work_exponent != kScaleFactorExponent) return ConstantsStatus::kOutOfRange;
  *out = decoded;
  return ConstantsStatus::kOk;
}

// q per axis: q ca^2 is formed as (ca^2 at 2 kAccelGExponent) * q, brought to kAccelGExponent by
// one SFTAC of (kAccelGExponent - 2 kAccelGExponent - e) bits, which must lie in -16..16; and
// |q| * (16 g)^2 < 16 g keeps the term inside the g format for any ca the stage can hold.
ConstantsStatus AccelQuadraticFromWords(const int16_t* words, CoeffQ31 out[3]) {
  CoeffQ31 decoded[3];
  for (uint8_t axis = 0; axis < 3; ++axis) {
    const ConstantsStatus s = CoeffFromWords(words + axis * kCoeffWords, &decoded[axis]);
    if (s != ConstantsStatus::kOk) return s;
    const int32_t shift = -kAccelGExponent - decoded[axis].exponent;
    if (shift < -kMaxAlignShift || shift > kMaxAlignShift) return ConstantsStatus::kOutOfRange;
    // |q| < 1/16 g per g^2  <=>  |m| 2^(e - 31) < 2^-4  <=>  |m| < 2^(27 - e).
    const int64_t abs_m = decoded[axis].mantissa_q31 < 0
                              ? -static_cast<int64_t>(decoded[axis].mantissa_q31)
                              : decoded[axis].mantissa_q31;
    const int32_t limit_log2 = 27 - decoded[axis].exponent;
    if (limit_log2 <= 31 && abs_m >= (static_cast<int64_t>(1) << limit_log2)) {
      return ConstantsStatus::kWouldOverflow;
    }
  }
  for (uint8_t axis = 0; axis < 3; ++axis) out[axis] = decoded[axis];
  return ConstantsStatus::kOk;
}

// value * 2^47 of a coefficient with exponent <= 16 (exact for exponent >= -16, floor below).
int64_t Units47(const CoeffQ31& c) {
  const int32_t shift = c.exponent + 16;
  if (shift >= 0) return static_cast<int64_t>(c.mantissa_q31) * (INT64_C(1) << shift);
  return static_cast<int64_t>(c.mantissa_q31) >> (-shift);
}

// units47 / 2^shift rounded to nearest (halves up). A value held as value 2^47 has the Q31
// mantissa RoundShift(units47, 16 + e) and the Q15 mantissa RoundShift(units47, 32 + e) at
// exponent e.
int64_t RoundShift(int64_t units47, int32_t shift) {
  if (shift <= 0) return units47;
  return (units47 + (INT64_C(1) << (shift - 1))) >> shift;
}

int16_t SatInt16(int64_t v) {
  return static_cast<int16_t>(v > INT16_MAX ? INT16_MAX : (v < INT16_MIN ? INT16_MIN : v));
}

// Sum of |Q15 mantissas| of `count` values at `exponent`.
int64_t SumAbsQ15(const int64_t* units47, uint8_t count, int32_t exponent) {
  int64_t sum_abs = 0;
  for (uint8_t k = 0; k < count; ++k) {
    const int64_t m = RoundShift(units47[k], 32 + exponent);
    sum_abs += m < 0 ? -m : m;
  }
  return sum_abs;
}

// Q15 mantissas at the smallest exponent, from `min_exponent` to kMaxQ15Exponent, whose rounded
// mantissas sum to at most 32767 in magnitude; returns that exponent.
constexpr int8_t kMinQ15Exponent = -16;
constexpr int8_t kMaxQ15Exponent = 2;
int8_t BlockQ15(const int64_t* units47, uint8_t count, int8_t min_exponent, int16_t* m_q15) {
  int8_t exponent = min_exponent;
  while (exponent < kMaxQ15Exponent && SumAbsQ15(units47, count, exponent) > INT16_MAX) ++exponent;
  for (uint8_t k = 0; k < count; ++k) m_q15[k] = SatInt16(RoundShift(units47[k], 32 + exponent));
  return exponent;
}

void ScaleTemperatureInit(ScaleTemperatureConstantsQ31* st) {
  st->enabled = 0;
  for (InputNormQ31& n : st->temp_norm) n = InputNormQ31{INT32_C(32768), 16};
  for (PolyQ31& f : st->scale) {
    ZeroPoly(&f, kScaleFactorExponent);
    f.coeff[0] = kOneCoeff;
  }
  for (CoeffQ31& q : st->accel_quadratic) q = kZeroCoeff;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) st->gs[r][c] = kZeroCoeff;
  }
  DeriveScaleTemperatureQ15(st);
}

ConstantsStatus ScaleTemperatureWriteBlock(ScaleTemperatureConstantsQ31* st,
                                           uint8_t block_id,
                                           const int16_t* words) {
  if (block_id == kImuBlockScaleSwitch) return ScaleSwitchFromWords(words, st);
  ConstantsStatus s = ConstantsStatus::kOk;
  if (block_id <= kImuBlockScaleFactorLast) {
    s = ScaleFactorFromWords(words, &st->scale[block_id - kImuBlockScaleFactorFirst]);
  } else if (block_id == kImuBlockAccelQuadratic) {
    s = AccelQuadraticFromWords(words, st->accel_quadratic);
  } else {
    s = MatrixFromWords(words, kRatedAccel_mps2, kRateExponent, st->gs);
  }
  if (s == ConstantsStatus::kOk) DeriveScaleTemperatureQ15(st);
  return s;
}

void ScaleTemperatureReadBlock(const ScaleTemperatureConstantsQ31& st,
                               uint8_t block_id,
                               int16_t* words) {
  if (block_id == kImuBlockScaleSwitch) {
    words[0] = st.enabled;
    for (uint8_t s = 0; s < kTempSensors; ++s)
      NormToWords(st.temp_norm[s], words + 1 + s * kNormWords);
  } else if (block_id <= kImuBlockScaleFactorLast) {
    PolyToWords(st.scale[block_id - kImuBlockScaleFactorFirst], kImuScaleFactorDegree, words);
  } else if (block_id == kImuBlockAccelQuadratic) {
    for (uint8_t axis = 0; axis < 3; ++axis) {
      CoeffToWords(st.accel_quadratic[axis], words + axis * kCoeffWords);
    }
  } else {
    MatrixToWords(st.gs, words);
  }
}

}  // namespace

void DeriveThermalAligned(ThermalConstantsQ31* thermal) {
  for (uint8_t k = 0; k <= kImuThermalDegree; ++k) {
    const CoeffQ31& c = thermal->drift.coeff[k];
    thermal->drift_aligned_q31[k] = c.mantissa_q31 >> (thermal->drift.work_exponent - c.exponent);
  }
}

void DeriveScaleDelta(const PolyQ31& scale, ScaleDeltaQ15* delta) {
  int64_t units47[kImuScaleFactorDegree + 1];
  for (uint8_t k = 0; k <= kImuScaleFactorDegree; ++k) units47[k] = Units47(scale.coeff[k]);
  units47[0] -= INT64_C(1) << 47;  // delta = F - 1
  // delta's exponent: the smallest whose Q31 holds |d0| + sum_k |d_k| with a margin of 4 2^16
  // LSB, which covers d1..d3 rounded to Q15 at an exponent no coarser (2^15 LSB each at most).
  int64_t sum_abs47 = 0;
  for (int64_t v : units47) sum_abs47 += v < 0 ? -v : v;
  int8_t exponent = kMinQ15Exponent;
  while (exponent < kMaxQ15Exponent &&
         RoundShift(sum_abs47, 16 + exponent) + 4 * (INT64_C(1) << 16) > INT32_MAX) {
    ++exponent;
  }
  const int8_t lowest = static_cast<int8_t>(exponent - 16);
  delta->tempco_exponent = BlockQ15(units47 + 1,
                                    kImuScaleFactorDegree,
                                    lowest < kMinQ15Exponent ? kMinQ15Exponent : lowest,
                                    delta->d_q15);
  if (delta->tempco_exponent > exponent) exponent = delta->tempco_exponent;
  delta->exponent = exponent;
  delta->d0_q31 = static_cast<int32_t>(RoundShift(units47[0], 16 + exponent));
}

void DeriveGSensitivity(const CoeffQ31 gs[3][3], GSensitivityQ15* out) {
  for (uint8_t r = 0; r < 3; ++r) {
    int64_t units47[3];
    for (uint8_t c = 0; c < 3; ++c) units47[c] = Units47(gs[r][c]);
    out->row_exponent[r] = BlockQ15(units47, 3, kMinQ15Exponent, out->m_q15[r]);
  }
}

int16_t DeriveQ15(const CoeffQ31& coeff) {
  const int64_t m = (static_cast<int64_t>(coeff.mantissa_q31) + (INT64_C(1) << 15)) >> 16;
  return static_cast<int16_t>(m > INT16_MAX ? INT16_MAX : m);
}

void DeriveScaleTemperatureQ15(ScaleTemperatureConstantsQ31* st) {
  for (uint8_t c = 0; c < kImuChannels; ++c) DeriveScaleDelta(st->scale[c], &st->delta[c]);
  for (uint8_t axis = 0; axis < 3; ++axis) {
    st->accel_quadratic_q15[axis] = DeriveQ15(st->accel_quadratic[axis]);
  }
  DeriveGSensitivity(st->gs, &st->gs_q15);
}

void ImuConstantsInit(ImuConstants* constants) {
  for (uint8_t c = 0; c < kImuChannels; ++c) {
    ThermalConstantsQ31& t = constants->thermal[c];
    t.temp_sensor =
        static_cast<uint8_t>(c < kAccelChannels ? c % kTempSensors : c - kAccelChannels);
    t.temp_norm = InputNormQ31{INT32_C(32768), 16};
    ZeroPoly(&t.drift, c < kAccelChannels ? kDutyExponent : kGyroCountExponent);
    DeriveThermalAligned(&t);
  }
  for (AccelScaleConstantsQ31& a : constants->accel) a = AccelScaleConstantsQ31{0, {0, 5}};
  for (GyroCubicConstantsQ31& g : constants->gyro) {
    g.count_norm = InputNormQ31{0, kGyroCountExponent};
    ZeroPoly(&g.rate, kRateExponent);
  }
  IdentityMatrix(constants->ca);
  IdentityMatrix(constants->cg);
  ScaleTemperatureInit(&constants->scale_temperature);
}

uint8_t ImuConstantsBlockLength(uint8_t block_id) {
  if (block_id >= kImuBlockThermalFirst && block_id <= kImuBlockThermalLast) {
    return kImuThermalBlockWords;
  }
  if (block_id == kImuBlockAccelOffsetScale) return kImuAccelBlockWords;
  if (block_id >= kImuBlockGyroCubicFirst && block_id <= kImuBlockGyroCubicLast) {
    return kImuGyroBlockWords;
  }
  if (block_id == kImuBlockCa || block_id == kImuBlockCg) return kImuMatrixBlockWords;
  if (block_id == kImuBlockScaleSwitch) return kImuScaleSwitchBlockWords;
  if (block_id >= kImuBlockScaleFactorFirst && block_id <= kImuBlockScaleFactorLast) {
    return kImuScaleFactorBlockWords;
  }
  if (block_id == kImuBlockAccelQuadratic) return kImuAccelQuadraticBlockWords;
  if (block_id == kImuBlockGs) return kImuMatrixBlockWords;
  return 0;
}

ConstantsStatus ImuConstantsWriteBlock(ImuConstants* constants,
                                       uint8_t block_id,
                                       const int16_t* words,
                                       uint8_t count) {
  if (constants == nullptr || words == nullptr) return ConstantsStatus::kNullArgument;
  const uint8_t length = ImuConstantsBlockLength(block_id);
  if (length == 0) return ConstantsStatus::kUnknownBlock;
  if (count != length) return ConstantsStatus::kWrongLength;
  if (block_id <= kImuBlockThermalLast) {
    const uint8_t channel = static_cast<uint8_t>(block_id - kImuBlockThermalFirst);
    return ThermalFromWords(words, channel, &constants->thermal[channel]);
  }
  if (block_id == kImuBlockAccelOffsetScale) return AccelFromWords(words, constants->accel);
  if (block_id <= kImuBlockGyroCubicLast) {
    return GyroFromWords(words, &constants->gyro[block_id - kImuBlockGyroCubicFirst]);
  }
  if (block_id == kImuBlockCa) {
    return MatrixFromWords(words, kRatedAccel_g, kAccelMps2Exponent, constants->ca);
  }
  if (block_id == kImuBlockCg) {
    return MatrixFromWords(words, kRatedRate_dps, kRateExponent, constants->cg);
  }
  return ScaleTemperatureWriteBlock(&constants->scale_temperature, block_id, words);
}

ConstantsStatus ImuConstantsReadBlock(const ImuConstants* constants,
                                      uint8_t block_id,
                                      int16_t* words,
                                      uint8_t capacity,
                                      uint8_t* count) {
  if (constants == nullptr || words == nullptr || count == nullptr) {
    return ConstantsStatus::kNullArgument;
  }
  const uint8_t length = ImuConstantsBlockLength(block_id);
  if (length == 0) return ConstantsStatus::kUnknownBlock;
  if (capacity < length) return ConstantsStatus::kWrongLength;
  if (block_id <= kImuBlockThermalLast) {
    const ThermalConstantsQ31& t = constants->thermal[block_id - kImuBlockThermalFirst];
    words[0] = t.temp_sensor;
    NormToWords(t.temp_norm, words + 1);
    PolyToWords(t.drift, kImuThermalDegree, words + 1 + kNormWords);
  } else if (block_id == kImuBlockAccelOffsetScale) {
    for (uint8_t c = 0; c < kAccelChannels; ++c) {
      int16_t* w = words + c * (2 + kCoeffWords);
      const uint32_t bits = static_cast<uint32_t>(constants->accel[c].offset_duty_q31);
      w[0] = static_cast<int16_t>(bits >> 16);
      w[1] = static_cast<int16_t>(bits & 0xFFFFu);
      CoeffToWords(constants->accel[c].inv_scale_g, w + 2);
    }
  } else if (block_id <= kImuBlockGyroCubicLast) {
    const GyroCubicConstantsQ31& g = constants->gyro[block_id - kImuBlockGyroCubicFirst];
    NormToWords(g.count_norm, words);
    PolyToWords(g.rate, 3, words + kNormWords);
  } else if (block_id <= kImuBlockCg) {
    MatrixToWords(block_id == kImuBlockCa ? constants->ca : constants->cg, words);
  } else {
    ScaleTemperatureReadBlock(constants->scale_temperature, block_id, words);
  }
  *count = length;
  return ConstantsStatus::kOk;
}

}  // namespace adahrs::firmware_model
