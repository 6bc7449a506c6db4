#include "ads_constants.h"

#include <stddef.h>

#include "air_data_tables.h"

// x and y normalisations (2 x 3 words), the outer working exponent, the 4 b_k working exponents.
#define HEAD_WORDS 11u
#define HYSTERESIS_OFFSET (HEAD_WORDS + (FW_SURFACE_TERMS * FW_COEFF_WORDS))
#define THERMAL_OFFSET (HYSTERESIS_OFFSET + FW_COEFF_WORDS + FW_GAIN_WORDS)
#define LINEARISATION_OFFSET (THERMAL_OFFSET + 3u + FW_COEFF_WORDS + FW_GAIN_WORDS)
#define TAU_EXPONENT 0

// The offsets add up to the block, whose last word is the law; b_k(y) fits a FwPolyQ31.
#if HEAD_WORDS != ((2u * FW_NORM_WORDS) + 1u + (FW_ADS_SURFACE_X_DEGREE + 1u))
#error "ADS surface block head does not add up"
#endif
#if (LINEARISATION_OFFSET + FW_BRIDGE_LINEARISATION_WORDS + 1u) != FW_ADS_SURFACE_BLOCK_WORDS
#error "ADS surface block layout does not add up"
#endif
#if FW_ADS_SURFACE_Y_DEGREE > FW_MAX_POLY_DEGREE
#error "b_k(y) does not fit a FwPolyQ31"
#endif

// Word offset of coefficient c_in (of y^n in b_i) in the block.
static uint16_t CoeffOffset(uint8_t i, uint8_t n) {
  const uint16_t term = (uint16_t)(((uint16_t)i * ((uint16_t)FW_ADS_SURFACE_Y_DEGREE + 1u)) + n);
  return (uint16_t)((uint16_t)HEAD_WORDS + ((uint16_t)FW_COEFF_WORDS * term));
}

static void ZeroSurface(FwSurfaceQ31* s, int8_t out_exponent) {
  const int8_t work_exponent = (int8_t)(out_exponent - 2);
  s->x_norm.centre = 0;
  s->x_norm.shift = 23u;
  s->y_norm = s->x_norm;
  s->outer_work_exponent = out_exponent;
  s->law = FW_ADS_LAW_DIRECT;
  s->pressure.inv_span.mantissa_q31 = 0;
  s->pressure.inv_span.exponent = 0;
  s->pressure.gain.at_centre_q15 = 0;
  s->pressure.gain.per_tau_q15 = 0;
  s->pressure.gain.exponent = work_exponent;
  s->thermal = s->pressure;
  for (uint8_t k = 0u; k < 3u; ++k) {
    s->die_temp_q15[k] = 0;
  }
  s->y_linearisation.raw_norm = s->x_norm;
  s->y_linearisation.curvature_q13 = 0;
  for (uint8_t i = 0u; i <= FW_ADS_SURFACE_X_DEGREE; ++i) {
    s->b[i].work_exponent = work_exponent;
    for (uint8_t k = 0u; k <= FW_MAX_POLY_DEGREE; ++k) {
      s->b[i].coeff[k].mantissa_q31 = 0;
      s->b[i].coeff[k].exponent = work_exponent;
    }
  }
}

// Outer Horner bound: with |b_k| < 2^E_k, every partial sum is below sum_k 2^E_k; require that
// sum <= 2^E_outer. Exponents are already range-checked, so E_outer - E_k is in 0..16.
static FwConstantsStatus ValidateOuter(const FwSurfaceQ31* s, int8_t out_exponent) {
  const int16_t bring = (int16_t)(s->outer_work_exponent - out_exponent);
  if ((s->outer_work_exponent < FW_MIN_EXPONENT) || (s->outer_work_exponent > FW_MAX_EXPONENT) ||
      (bring < -FW_MAX_ALIGN_SHIFT) || (bring > FW_MAX_ALIGN_SHIFT)) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  int64_t sum = 0;  // in units of 2^(E_outer - 16)
  for (uint8_t i = 0u; i <= FW_ADS_SURFACE_X_DEGREE; ++i) {
    const int16_t align = (int16_t)(s->outer_work_exponent - s->b[i].work_exponent);
    if ((align < 0) || (align > FW_MAX_ALIGN_SHIFT)) {
      return FW_CONSTANTS_OUT_OF_RANGE;
    }
    const int16_t weight_log2 = (int16_t)(FW_MAX_ALIGN_SHIFT - align);
    sum += INT64_C(1) << (uint8_t)weight_log2;
  }
  return (sum > (INT64_C(1) << FW_MAX_ALIGN_SHIFT)) ? FW_CONSTANTS_WOULD_OVERFLOW : FW_CONSTANTS_OK;
}

// A hysteresis term from its 6 words (docs/firmware-compensator.md "Hysteresis compensation").
static FwConstantsStatus TermFromWords(const int16_t* words,
                                       int8_t input_exponent,
                                       int8_t result_exponent,
                                       FwHysteresisTermQ* term) {
  const FwConstantsStatus s = fw_coeff_from_words(words, &term->inv_span);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  term->gain.at_centre_q15 = words[FW_COEFF_WORDS];
  term->gain.per_tau_q15 = words[FW_COEFF_WORDS + 1u];
  term->gain.exponent = (int8_t)words[FW_COEFF_WORDS + 2u];
  const int16_t travel_shift = (int16_t)(input_exponent + term->inv_span.exponent);
  const int32_t gain_align = (int32_t)result_exponent - (int32_t)words[FW_COEFF_WORDS + 2u];
  if ((term->inv_span.mantissa_q31 == INT32_MIN) || (travel_shift < -31) || (travel_shift > 31) ||
      (gain_align < 0) || (gain_align > FW_MAX_ALIGN_SHIFT)) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  return FW_CONSTANTS_OK;
}

static void TermToWords(const FwHysteresisTermQ* term, int16_t* words) {
  fw_coeff_to_words(&term->inv_span, words);
  words[FW_COEFF_WORDS] = term->gain.at_centre_q15;
  words[FW_COEFF_WORDS + 1u] = term->gain.per_tau_q15;
  words[FW_COEFF_WORDS + 2u] = term->gain.exponent;
}

// The four b_k(y) of a surface block: working exponents, then each polynomial's coefficients.
static FwConstantsStatus SurfacePolysFromWords(const int16_t* words, FwSurfaceQ31* decoded) {
  const int16_t* w = &words[2u * FW_NORM_WORDS];
  for (uint8_t i = 0u; i < (1u + FW_ADS_SURFACE_X_DEGREE + 1u); ++i) {
    if ((w[i] < FW_MIN_EXPONENT) || (w[i] > FW_MAX_EXPONENT)) {
      return FW_CONSTANTS_OUT_OF_RANGE;
    }
  }
  decoded->outer_work_exponent = (int8_t)w[0];
  for (uint8_t i = 0u; i <= FW_ADS_SURFACE_X_DEGREE; ++i) {
    FwPolyQ31* b = &decoded->b[i];
    b->work_exponent = (int8_t)w[1u + i];
    for (uint8_t k = 0u; k <= FW_MAX_POLY_DEGREE; ++k) {
      b->coeff[k].mantissa_q31 = 0;
      b->coeff[k].exponent = b->work_exponent;
    }
    for (uint8_t n = 0u; n <= FW_ADS_SURFACE_Y_DEGREE; ++n) {
      const FwConstantsStatus s = fw_coeff_from_words(&words[CoeffOffset(i, n)], &b->coeff[n]);
      if (s != FW_CONSTANTS_OK) {
        return s;
      }
    }
    const FwConstantsStatus s = fw_validate_poly(b, FW_ADS_SURFACE_Y_DEGREE);
    if (s != FW_CONSTANTS_OK) {
      return s;
    }
  }
  return FW_CONSTANTS_OK;
}

static FwConstantsStatus SurfaceFromWords(const int16_t* words,
                                          int8_t out_exponent,
                                          uint8_t pressure_law,
                                          FwSurfaceQ31* out) {
  FwSurfaceQ31 decoded = {0};
  const int16_t law = words[FW_ADS_SURFACE_BLOCK_WORDS - 1u];
  if ((law != (int16_t)FW_ADS_LAW_DIRECT) && (law != (int16_t)pressure_law)) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  decoded.law = (uint8_t)law;
  FwConstantsStatus s = fw_norm_from_words(words, 31u, &decoded.x_norm);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  s = fw_norm_from_words(&words[FW_NORM_WORDS], 31u, &decoded.y_norm);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  s = SurfacePolysFromWords(words, &decoded);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  const int8_t result_exponent = fw_ads_surface_exponent(decoded.law, out_exponent);
  s = ValidateOuter(&decoded, result_exponent);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  s = TermFromWords(&words[HYSTERESIS_OFFSET], result_exponent, result_exponent, &decoded.pressure);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  int32_t tau_bound = 0;
  for (uint8_t k = 0u; k < 3u; ++k) {
    decoded.die_temp_q15[k] = words[THERMAL_OFFSET + k];
    tau_bound += (decoded.die_temp_q15[k] < 0) ? -(int32_t)decoded.die_temp_q15[k]
                                               : (int32_t)decoded.die_temp_q15[k];
  }
  if (tau_bound > INT16_MAX) {
    return FW_CONSTANTS_WOULD_OVERFLOW;
  }
  s = TermFromWords(&words[THERMAL_OFFSET + 3u], TAU_EXPONENT, result_exponent, &decoded.thermal);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  s = fw_bridge_linearisation_from_words(&words[LINEARISATION_OFFSET], &decoded.y_linearisation);
  if (s != FW_CONSTANTS_OK) {
    return s;
  }
  *out = decoded;
  return FW_CONSTANTS_OK;
}

static void SurfaceToWords(const FwSurfaceQ31* s, int16_t* words) {
  fw_norm_to_words(&s->x_norm, words);
  fw_norm_to_words(&s->y_norm, &words[FW_NORM_WORDS]);
  int16_t* w = &words[2u * FW_NORM_WORDS];
  w[0] = s->outer_work_exponent;
  for (uint8_t i = 0u; i <= FW_ADS_SURFACE_X_DEGREE; ++i) {
    w[1u + i] = s->b[i].work_exponent;
    for (uint8_t n = 0u; n <= FW_ADS_SURFACE_Y_DEGREE; ++n) {
      fw_coeff_to_words(&s->b[i].coeff[n], &words[CoeffOffset(i, n)]);
    }
  }
  TermToWords(&s->pressure, &words[HYSTERESIS_OFFSET]);
  for (uint8_t k = 0u; k < 3u; ++k) {
    words[THERMAL_OFFSET + k] = s->die_temp_q15[k];
  }
  TermToWords(&s->thermal, &words[THERMAL_OFFSET + 3u]);
  fw_bridge_linearisation_to_words(&s->y_linearisation, &words[LINEARISATION_OFFSET]);
  words[FW_ADS_SURFACE_BLOCK_WORDS - 1u] = (int16_t)s->law;
}

int8_t fw_ads_surface_exponent(uint8_t law, int8_t out_exponent) {
  return (law == FW_ADS_LAW_DIRECT) ? out_exponent : (int8_t)FW_PRESSURE_EXPONENT;
}

void fw_ads_constants_init(FwAdsConstants* constants) {
  ZeroSurface(&constants->altitude, FW_ALTITUDE_EXPONENT);
  ZeroSurface(&constants->airspeed, FW_AIRSPEED_EXPONENT);
}

uint8_t fw_ads_constants_block_length(uint8_t block_id) {
  return ((block_id == FW_ADS_BLOCK_ALTITUDE) || (block_id == FW_ADS_BLOCK_AIRSPEED))
             ? (uint8_t)FW_ADS_SURFACE_BLOCK_WORDS
             : 0u;
}

FwConstantsStatus fw_ads_constants_write_block(FwAdsConstants* constants,
                                               uint8_t block_id,
                                               const int16_t* words,
                                               uint8_t count) {
  if ((constants == NULL) || (words == NULL)) {
    return FW_CONSTANTS_NULL_ARGUMENT;
  }
  const uint8_t length = fw_ads_constants_block_length(block_id);
  if (length == 0u) {
    return FW_CONSTANTS_UNKNOWN_BLOCK;
  }
  if (count != length) {
    return FW_CONSTANTS_WRONG_LENGTH;
  }
  return (block_id == FW_ADS_BLOCK_ALTITUDE)
             ? SurfaceFromWords(
                   words, FW_ALTITUDE_EXPONENT, FW_ADS_LAW_ISA_ALTITUDE, &constants->altitude)
             : SurfaceFromWords(words, FW_AIRSPEED_EXPONENT, FW_ADS_LAW_CAS, &constants->airspeed);
}

FwConstantsStatus fw_ads_constants_read_block(const FwAdsConstants* constants,
                                              uint8_t block_id,
                                              int16_t* words,
                                              uint8_t capacity,
                                              uint8_t* count) {
  if ((constants == NULL) || (words == NULL) || (count == NULL)) {
    return FW_CONSTANTS_NULL_ARGUMENT;
  }
  const uint8_t length = fw_ads_constants_block_length(block_id);
  if (length == 0u) {
    return FW_CONSTANTS_UNKNOWN_BLOCK;
  }
  if (capacity < length) {
    return FW_CONSTANTS_WRONG_LENGTH;
  }
  SurfaceToWords((block_id == FW_ADS_BLOCK_ALTITUDE) ? &constants->altitude : &constants->airspeed,
                 words);
  *count = length;
  return FW_CONSTANTS_OK;
}
