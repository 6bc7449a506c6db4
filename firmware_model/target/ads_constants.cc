#include "firmware_model/target/ads_constants.h"

#include "firmware_model/target/air_data_tables.h"

namespace adahrs::firmware_model {
namespace {

constexpr uint8_t kHeadWords = 2 * kNormWords + 1 + (kAdsSurfaceXDegree + 1);

// Word offset of coefficient c_in (of y^n in b_i) in the block.
uint8_t CoeffOffset(uint8_t i, uint8_t n) {
  return static_cast<uint8_t>(kHeadWords + kCoeffWords * (i * (kAdsSurfaceYDegree + 1) + n));
}

constexpr uint8_t kHysteresisOffset = kHeadWords + kSurfaceTerms * kCoeffWords;
constexpr uint8_t kThermalOffset = kHysteresisOffset + kCoeffWords + kGainWords;
constexpr uint8_t kLinearisationOffset = kThermalOffset + 3 + kCoeffWords + kGainWords;
static_assert(kLinearisationOffset + kBridgeLinearisationWords + 1 == kAdsSurfaceBlockWords);
constexpr int8_t kTauExponent = 0;

void ZeroSurface(SurfaceQ31* s, int8_t out_exponent) {
  s->x_norm = InputNormQ31{0, 23};
  s->y_norm = InputNormQ31{0, 23};
  s->outer_work_exponent = out_exponent;
  s->law = kAdsLawDirect;
  const HysteresisTermQ off{CoeffQ31{0, 0}, GainQ15{0, 0, static_cast<int8_t>(out_exponent - 2)}};
  s->pressure = off;
  s->thermal = off;
  for (int16_t& t : s->die_temp_q15) t = 0;
  s->y_linearisation = BridgeLinearisationQ{InputNormQ31{0, 23}, 0};
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

// A hysteresis term from its 6 words (docs/firmware-compensator.md "Hysteresis compensation").
ConstantsStatus TermFromWords(const int16_t* words,
                              int8_t input_exponent,
                              int8_t result_exponent,
                              HysteresisTermQ* term) {
  const ConstantsStatus s = CoeffFromWords(words, &term->inv_span);
  if (s != ConstantsStatus::kOk) return s;
  term->gain = GainQ15{
      words[kCoeffWords], words[kCoeffWords + 1], static_cast<int8_t>(words[kCoeffWords + 2])};
  const int32_t travel_shift = input_exponent + term->inv_span.exponent;
  const int32_t gain_align = result_exponent - words[kCoeffWords + 2];
  if (term->inv_span.mantissa_q31 == INT32_MIN || travel_shift < -31 || travel_shift > 31 ||
      gain_align < 0 || gain_align > kMaxAlignShift) {
    return ConstantsStatus::kOutOfRange;
  }
  return ConstantsStatus::kOk;
}

void TermToWords(const HysteresisTermQ& term, int16_t* words) {
  CoeffToWords(term.inv_span, words);
  words[kCoeffWords] = term.gain.at_centre_q15;
  words[kCoeffWords + 1] = term.gain.per_tau_q15;
  words[kCoeffWords + 2] = term.gain.exponent;
}

ConstantsStatus SurfaceFromWords(const int16_t* words,
                                 int8_t out_exponent,
                                 uint8_t pressure_law,
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
  const int8_t result_exponent = AdsSurfaceExponent(decoded.law, out_exponent);
  s = ValidateOuter(decoded, result_exponent);
  if (s != ConstantsStatus::kOk) return s;
  s = TermFromWords(words + kHysteresisOffset, result_exponent, result_exponent, &decoded.pressure);
  if (s != ConstantsStatus::kOk) return s;
  int32_t tau_bound = 0;
  for (uint8_t k = 0; k < 3; ++k) {
    decoded.die_temp_q15[k] = words[kThermalOffset + k];
    tau_bound += decoded.die_temp_q15[k] < 0 ? -decoded.die_temp_q15[k] : decoded.die_temp_q15[k];
  }
  if (tau_bound > INT16_MAX) return ConstantsStatus::kWouldOverflow;
  s = TermFromWords(words + kThermalOffset + 3, kTauExponent, result_exponent, &decoded.thermal);
  if (s != ConstantsStatus::kOk) return s;
  s = BridgeLinearisationFromWords(words + kLinearisationOffset, &decoded.y_linearisation);
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
    for (uint8_t n = 0; n <= kAdsSurfaceYDegree; ++n)
      CoeffToWords(s.b[i].coeff[n], words + CoeffOffset(i, n));
  }
  TermToWords(s.pressure, words + kHysteresisOffset);
  for (uint8_t k = 0; k < 3; ++k) words[kThermalOffset + k] = s.die_temp_q15[k];
  TermToWords(s.thermal, words + kThermalOffset + 3);
  BridgeLinearisationToWords(s.y_linearisation, words + kLinearisationOffset);
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

ConstantsStatus AdsConstantsWriteBlock(AdsConstants* constants,
                                       uint8_t block_id,
                                       const int16_t* words,
                                       uint8_t count) {
  if (constants == nullptr || words == nullptr) return ConstantsStatus::kNullArgument;
  const uint8_t length = AdsConstantsBlockLength(block_id);
  if (length == 0) return ConstantsStatus::kUnknownBlock;
  if (count != length) return ConstantsStatus::kWrongLength;
  if (block_id == kAdsBlockAltitude) {
    return SurfaceFromWords(words, kAltitudeExponent, kAdsLawIsaAltitude, &constants->altitude);
  }
  return SurfaceFromWords(words, kAirspeedExponent, kAdsLawCas, &constants->airspeed);
}

ConstantsStatus AdsConstantsReadBlock(const AdsConstants* constants,
                                      uint8_t block_id,
                                      int16_t* words,
                                      uint8_t capacity,
                                      uint8_t* count) {
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
