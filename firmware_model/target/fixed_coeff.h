// Fixed-point building blocks shared by the IMU and ADS constant sets (target code, dsPIC30F/33F).
// Every stored quantity is a Q31 mantissa m (int32_t) with an exponent e (int8_t):
// value = m * 2^(e - 31), |value| < 2^e; a raw integer such as an ADC code has e = 31. Exponents
// are chosen offline by the host exporter (firmware_model/constants_exporter.h), so every
// coefficient keeps 31 significant bits. A polynomial is evaluated in x = (v - centre) * 2^-shift,
// held in Q31 (|x| < 1): a power-of-two scale makes the normalisation an exact shift of the centred
// 32-bit value, and the centre removes the large common part of, e.g., a 24-bit ADC code before
// any multiply. Words on the maintenance port (int16, big part first): FwCoeffQ31 3,
// FwInputNormQ31 3, FwPolyQ31 1 + 3*(degree+1).
// Number formats, normalisation and word layouts: docs/firmware-compensator.md ("Number formats",
// "Normalisation").
// Not modelled here: the meaning of each block (see imu_constants.h, ads_constants.h).
#ifndef ADAHRS_FW_FIXED_COEFF_H
#define ADAHRS_FW_FIXED_COEFF_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Outcome of writing or reading one constant block; the maintenance handler maps it to a NAK code.
typedef enum {
  FW_CONSTANTS_OK = 0,
  FW_CONSTANTS_UNKNOWN_BLOCK = 1,   ///< block id is not defined for this unit
  FW_CONSTANTS_WRONG_LENGTH = 2,    ///< word count differs from the block's fixed length
  FW_CONSTANTS_OUT_OF_RANGE = 3,    ///< a field lies outside its documented range
  FW_CONSTANTS_WOULD_OVERFLOW = 4,  ///< representable but could overflow a Q31 stage
  FW_CONSTANTS_NULL_ARGUMENT = 5    ///< a pointer argument is null
} FwConstantsStatus;

/// One coefficient: value = mantissa_q31 * 2^(exponent - 31).
typedef struct {
  int32_t mantissa_q31;
  int8_t exponent;
} FwCoeffQ31;

/// Input normalisation x = (v - centre) * 2^-shift, with v and centre in the input's own format.
typedef struct {
  int32_t centre;
  uint8_t shift;
} FwInputNormQ31;

/// Largest polynomial degree any stage uses: the gyro's Eq. 23 and the thermal drift are cubic,
/// the ADS surface's temperature polynomials b_k(y) are of degree 5 (ads_constants.h).
#define FW_MAX_POLY_DEGREE 5u

/// p(x) = sum c_k x^k, evaluated by Horner at the working exponent: every partial sum is a Q31
/// mantissa at `work_exponent`, coefficient k is aligned by the constant right shift
/// (work_exponent - coeff[k].exponent), which must lie in 0..16 (one SFTAC).
typedef struct {
  FwCoeffQ31 coeff[FW_MAX_POLY_DEGREE + 1u];
  int8_t work_exponent;
} FwPolyQ31;

/// Exponent range accepted in any coefficient or working exponent.
#define FW_MIN_EXPONENT (-40)
#define FW_MAX_EXPONENT 40
/// Largest alignment shift between a coefficient and its working exponent (one SFTAC, 16 bits).
#define FW_MAX_ALIGN_SHIFT 16

#define FW_COEFF_WORDS 3u
#define FW_NORM_WORDS 3u

/// Words of a FwPolyQ31 of degree `degree` (a constant expression for a constant degree).
#define FW_POLY_WORDS(degree) (1u + (FW_COEFF_WORDS * ((degree) + 1u)))

/// Decodes a coefficient from 3 words; OUT_OF_RANGE if the exponent is outside the accepted range.
FwConstantsStatus fw_coeff_from_words(const int16_t* words, FwCoeffQ31* coeff);
void fw_coeff_to_words(const FwCoeffQ31* coeff, int16_t* words);

/// Decodes a normalisation; OUT_OF_RANGE unless 0 <= shift <= max_shift.
FwConstantsStatus fw_norm_from_words(const int16_t* words, uint8_t max_shift, FwInputNormQ31* norm);
void fw_norm_to_words(const FwInputNormQ31* norm, int16_t* words);

/// Decodes a polynomial of `degree` (coefficients above it are set to zero) and validates it:
/// OUT_OF_RANGE for a bad exponent or an alignment shift outside 0..16; WOULD_OVERFLOW unless
/// sum_k |c_k| < 2^work_exponent, which guarantees that no Horner partial sum overflows for
/// |x| <= 1.
FwConstantsStatus fw_poly_from_words(const int16_t* words, uint8_t degree, FwPolyQ31* poly);
void fw_poly_to_words(const FwPolyQ31* poly, uint8_t degree, int16_t* words);

/// OK if every alignment shift is valid and sum_k |c_k| < 2^work_exponent (see fw_poly_from_words).
FwConstantsStatus fw_validate_poly(const FwPolyQ31* poly, uint8_t degree);

/// The 32-bit value of a word pair, high word first (both as int16 bit patterns).
int32_t fw_join32(int16_t high, int16_t low);
/// The high and low words of a 32-bit value, as int16 bit patterns.
int16_t fw_high16(int32_t v);
int16_t fw_low16(int32_t v);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_FIXED_COEFF_H
