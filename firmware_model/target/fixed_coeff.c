#include "fixed_coeff.h"

#include "q_math.h"

int32_t fw_join32(int16_t high, int16_t low) { return fw_join_words(high, (uint16_t)low); }

int16_t fw_high16(int32_t v) { return fw_high_word(v); }

int16_t fw_low16(int32_t v) { return fw_s16_from_bits(fw_low_word(v)); }

static int64_t Abs64(int32_t v) { return (v < 0) ? -(int64_t)v : (int64_t)v; }

FwConstantsStatus fw_coeff_from_words(const int16_t* words, FwCoeffQ31* coeff) {
  if ((words[2] < FW_MIN_EXPONENT) || (words[2] > FW_MAX_EXPONENT)) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  coeff->mantissa_q31 = fw_join32(words[0], words[1]);
  coeff->exponent = (int8_t)words[2];
  return FW_CONSTANTS_OK;
}

void fw_coeff_to_words(const FwCoeffQ31* coeff, int16_t* words) {
  words[0] = fw_high16(coeff->mantissa_q31);
  words[1] = fw_low16(coeff->mantissa_q31);
  words[2] = coeff->exponent;
}

FwConstantsStatus fw_norm_from_words(const int16_t* words,
                                     uint8_t max_shift,
                                     FwInputNormQ31* norm) {
  if ((words[2] < 0) || (words[2] > (int16_t)max_shift)) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  norm->centre = fw_join32(words[0], words[1]);
  norm->shift = (uint8_t)words[2];
  return FW_CONSTANTS_OK;
}

void fw_norm_to_words(const FwInputNormQ31* norm, int16_t* words) {
  words[0] = fw_high16(norm->centre);
  words[1] = fw_low16(norm->centre);
  words[2] = (int16_t)norm->shift;
}

FwConstantsStatus fw_validate_poly(const FwPolyQ31* poly, uint8_t degree) {
  if ((degree > FW_MAX_POLY_DEGREE) || (poly->work_exponent < FW_MIN_EXPONENT) ||
      (poly->work_exponent > FW_MAX_EXPONENT)) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  // sum_k |m_k| 2^(e_k - E) < 2^31, accumulated in units of 2^-16 of a Q31 LSB so that every
  // alignment shift (0..16) is exact; the bound then also covers the Horner partial sums.
  int64_t sum_abs = 0;
  for (uint8_t k = 0u; k <= degree; ++k) {
    const int16_t align =
        (int16_t)((int16_t)poly->work_exponent - (int16_t)poly->coeff[k].exponent);
    if ((align < 0) || (align > FW_MAX_ALIGN_SHIFT)) {
      return FW_CONSTANTS_OUT_OF_RANGE;
    }
    const int16_t weight_log2 = (int16_t)(FW_MAX_ALIGN_SHIFT - align);
    sum_abs += Abs64(poly->coeff[k].mantissa_q31) * (INT64_C(1) << (uint8_t)weight_log2);
  }
  if (sum_abs >= (INT64_C(1) << (31 + FW_MAX_ALIGN_SHIFT))) {
    return FW_CONSTANTS_WOULD_OVERFLOW;
  }
  return FW_CONSTANTS_OK;
}

FwConstantsStatus fw_poly_from_words(const int16_t* words, uint8_t degree, FwPolyQ31* poly) {
  if (degree > FW_MAX_POLY_DEGREE) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  if ((words[0] < FW_MIN_EXPONENT) || (words[0] > FW_MAX_EXPONENT)) {
    return FW_CONSTANTS_OUT_OF_RANGE;
  }
  FwPolyQ31 decoded;
  decoded.work_exponent = (int8_t)words[0];
  for (uint8_t k = 0u; k <= FW_MAX_POLY_DEGREE; ++k) {
    decoded.coeff[k].mantissa_q31 = 0;
    decoded.coeff[k].exponent = decoded.work_exponent;
  }
  for (uint8_t k = 0u; k <= degree; ++k) {
    const FwConstantsStatus status =
        fw_coeff_from_words(&words[1u + (FW_COEFF_WORDS * k)], &decoded.coeff[k]);
    if (status != FW_CONSTANTS_OK) {
      return status;
    }
  }
  const FwConstantsStatus status = fw_validate_poly(&decoded, degree);
  if (status != FW_CONSTANTS_OK) {
    return status;
  }
  *poly = decoded;
  return FW_CONSTANTS_OK;
}

void fw_poly_to_words(const FwPolyQ31* poly, uint8_t degree, int16_t* words) {
  words[0] = poly->work_exponent;
  for (uint8_t k = 0u; k <= degree; ++k) {
    fw_coeff_to_words(&poly->coeff[k], &words[1u + (FW_COEFF_WORDS * k)]);
  }
}
