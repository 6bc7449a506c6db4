#include "firmware_model/target/ads_constants.h"

#include "firmware_model/target/air_data_tables.h"

namespace adahrs::firmware_model {
namespace {

constexpr uint8_t kHeadWords = 2 * kNormWords + 1 + (kAdsSurfaceXDegree + 1);

// Word offset of coefficient c_in (of y^n in b_i) in the block.
uint8_t CoeffOffset(uint8_t i, uint8_t n) {
  return static_cast<uint8_t>(kHeadWords + kCoeffWords * (i * (kAdsSurfaceYDegree + 1) + n));
}

void ZeroSurface(SurfaceQ31* s, int8_t out_exponent) {
  s->x_norm = InputNormQ31{0, 23};
  s->y_norm = InputNormQ31{0, 23};
  s->outer_work_exponent = out_exponent;
  s->law = kAdsLawDirect;
  for (PolyQ31& b : s->b) {
    b.work_exponent = static_cast<int8_t>(out_exponent - 2);
    for (CoeffQ31& c : b.coeff) c = CoeffQ31{0, b.work_exponent};
  }
}

// Outer Horner bound: with |b_k| < 2^E_k, every partial sum is below sum_k 2^E_k; require that
// sum <= 2^E_outer. Exponents are already range-checked, so E_outer - E_k is in 0..16.
ConstantsStatus ValidateOuter(const SurfaceQ31& s, int8_t out_exponent) {
  const int32_t bring = s.outer_work_exponent - out_exponent;
  if (s.outer_work_exponent < kMinExponent || s.outer_work_exponent > kMaxExponent ||
      bring < -kMaxAlignShift || bring > kMaxAlignShift) {
    return ConstantsStatus::kOutOfRange;
  }
  int64_t sum = 0;  // in units of 2^(E_outer - 16)
  for (const PolyQ31& b : s.b) {
    const int32_t align = s.outer_work_exponent - b.work_exponent;
    if (align < 0 || align > kMaxAlignShift) return ConstantsStatus::kOutOfRange;
    sum += static_cast<int64_t>(1) << (kMaxAlignShift - align);
  }
  if (sum > (static_cast<int64_t>(1) << kMaxAlignShift)) return ConstantsStatus::kWouldOverflow;
  return ConstantsStatus::kOk;
}

ConstantsStatus SurfaceFromWords(const int16_t* words, int8_t out_exponent, uint8_t pressure_law,
                                 SurfaceQ31* out) {
  SurfaceQ31 decoded{};
  const int16_t law = words[kAdsSurfaceBlockWords - 1];
  if (law != kAdsLawDirect && law != pressure_law) return ConstantsStatus::kOutOfRange;
  decoded.law = static_cast<uint8_t>(law);
  ConstantsStatus s = NormFromWords(words, 31, &decoded.x_norm);
  if (s != ConstantsStatus::kOk) return s;
  s = NormFromWords(words + kNormWords, 31, &decoded.y_norm);
  if (s != ConstantsStatus::kOk) return s;
  const int16_t* w = words + 2 * kNormWords;
  for (uint8_t i = 0; i < 1 + kAdsSurfaceXDegree + 1; ++i) {
    if (w[i] < kMinExponent || w[i] > kMaxExponent) return ConstantsStatus::kOutOfRange;
  }
  decoded.outer_work_exponent = static_cast<int8_t>(w[0]);
  for (uint8_t i = 0; i <= kAdsSurfaceXDegree; ++i) {
    PolyQ31& b = decoded.b[i];
    b.work_exponent = static_cast<int8_t>(w[1 + i]);
    for (uint8_t k = 0; k <= kMaxPolyDegree; ++k) b.coeff[k] = CoeffQ31{0, b.work_exponent};
    for (uint8_t n = 0; n <= kAdsSurfaceYDegree; ++n) {
      s = CoeffFromWords(words + CoeffOffset(i, n), &b.coeff[n]);
      if (s != ConstantsStatus::kOk) return s;
    }
    s = ValidatePoly(b, kAdsSurfaceYDegree);
    if (s != ConstantsStatus::kOk) return s;
  }
  s = ValidateOuter(decoded, AdsSurfaceExponent(decoded.law, out_exponent));
  if (s != ConstantsStatus::kOk) return s;
  *out = decoded;
  return ConstantsStatus::kOk;
}

void SurfaceToWords(const SurfaceQ31& s, int16_t* words) {
  NormToWords(s.x_norm, words);
  NormToWords(s.y_norm, words + kNormWords);
  int16_t* w = words + 2 * kNormWords;
  w[0] = s.outer_work_exponent;
  for (uint8_t i = 0; i <= kAdsSurfaceXDegree; ++i) {
    w[1 + i] = s.b[i].work_exponent;
    for (uint8_t n = 0; n <= kAdsSurfaceYDegree; ++n) CoeffToWords(s.b[i].coeff[n], words + CoeffOffset(i, n));
  }
  words[kAdsSurfaceBlockWords - 1] = s.law;
}

}  // namespace

int8_t AdsSurfaceExponent(uint8_t law, int8_t out_exponent) {
  return law == kAdsLawDirect ? out_exponent : kPressureExponent;
}

void AdsConstantsInit(AdsConstants* constants) {
  ZeroSurface(&constants->altitude, kAltitudeExponent);
  ZeroSurface(&constants->airspeed, kAirspeedExponent);
}

uint8_t AdsConstantsBlockLength(uint8_t block_id) {
  return (block_id == kAdsBlockAltitude || block_id == kAdsBlockAirspeed) ? kAdsSurfaceBlockWords
                                                                          : 0;
}

ConstantsStatus AdsConstantsWriteBlock(AdsConstants* constants, uint8_t block_id,
                                       const int16_t* words, uint8_t count) {
  if (constants == nullptr || words == nullptr) return ConstantsStatus::kNullArgument;
  const uint8_t length = AdsConstantsBlockLength(block_id);
  if (length == 0) return ConstantsStatus::kUnknownBlock;
  if (count != length) return ConstantsStatus::kWrongLength;
  if (block_id == kAdsBlockAltitude) {
    return SurfaceFromWords(words, kAltitudeExponent, kAdsLawIsaAltitude, &constants->altitude);
  }
  return SurfaceFromWords(words, kAirspeedExponent, kAdsLawCas, &constants->airspeed);
}

ConstantsStatus AdsConstantsReadBlock(const AdsConstants* constants, uint8_t block_id,
                                      int16_t* words, uint8_t capacity, uint8_t* count) {
  if (constants == nullptr || words == nullptr || count == nullptr) {
    return ConstantsStatus::kNullArgument;
  }
  const uint8_t length = AdsConstantsBlockLength(block_id);
  if (length == 0) return ConstantsStatus::kUnknownBlock;
  if (capacity < length) return ConstantsStatus::kWrongLength;
  SurfaceToWords(block_id == kAdsBlockAltitude ? constants->altitude : constants->airspeed, words);
  *count = length;
  return ConstantsStatus::kOk;
}

}  // namespace adahrs::firmware_model
