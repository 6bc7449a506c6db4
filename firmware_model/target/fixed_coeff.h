// Fixed-point building blocks shared by the IMU and ADS constant sets (target code, dsPIC30F/33F).
//
// Number format. Every stored quantity is a Q31 mantissa m (int32_t) with an exponent e (int8_t):
//   value = m * 2^(e - 31),   |value| < 2^e.
// A raw integer such as an ADC code is the same format with e = 31. The exponent is a block
// exponent chosen offline by the host exporter (firmware_model/constants_exporter.h), so a
// coefficient such as 4.2e6 counts and one of 1e-20 deg/s per count^3 both keep 31 significant
// bits (physics.md section 5.3, "Horner with per-coefficient Q scaling").
//
// Input normalisation. A polynomial is evaluated in x = (v - centre) * 2^-shift, held in Q31, so
// |x| < 1. The scale is a power of two on purpose: the normalisation is then an exact shift of the
// centred 32-bit value (no rounding error, one SFTAC on the target), and the centre removes the
// large common part of, e.g., a 24-bit ADC code before any multiply.
//
// Word layout (the maintenance port carries int16 words, big part first):
//   CoeffQ31      3 words: mantissa bits 31..16, mantissa bits 15..0 (as int16 bit pattern), e
//   InputNormQ31  3 words: centre bits 31..16, centre bits 15..0, shift
//   PolyQ31       1 + 3*(degree+1) words: working exponent, then coefficients c0 .. c_degree
// Not modelled here: the meaning of each block (see imu_constants.h, ads_constants.h).
#pragma once

#include <cstdint>

namespace adahrs::firmware_model {

/// Outcome of writing or reading one constant block; the maintenance handler maps it to a NAK code.
enum class ConstantsStatus : uint8_t {
  kOk = 0,
  kUnknownBlock = 1,   ///< block id is not defined for this unit
  kWrongLength = 2,    ///< word count differs from the block's fixed length
  kOutOfRange = 3,     ///< a field lies outside its documented range (exponent, shift, index)
  kWouldOverflow = 4,  ///< the set is representable but could overflow a Q31 stage in the envelope
  kNullArgument = 5,   ///< a pointer argument is null
};

/// One coefficient: value = mantissa_q31 * 2^(exponent - 31).
struct CoeffQ31 {
  int32_t mantissa_q31;
  int8_t exponent;
};

/// Input normalisation x = (v - centre) * 2^-shift, with v and centre in the input's own format.
struct InputNormQ31 {
  int32_t centre;
  uint8_t shift;
};

/// Largest polynomial degree any stage uses: the gyro's Eq. 23 and the thermal drift are cubic,
/// the ADS surface's temperature polynomials b_k(y) are of degree 5 (ads_constants.h).
inline constexpr uint8_t kMaxPolyDegree = 5;

/// p(x) = sum c_k x^k, evaluated by Horner at the working exponent: every partial sum is a Q31
/// mantissa at `work_exponent`, coefficient k is aligned by the constant right shift
/// (work_exponent - coeff[k].exponent), which must lie in 0..16 (one SFTAC).
struct PolyQ31 {
  CoeffQ31 coeff[kMaxPolyDegree + 1];
  int8_t work_exponent;
};

/// Exponent range accepted in any coefficient or working exponent.
inline constexpr int8_t kMinExponent = -40;
inline constexpr int8_t kMaxExponent = 40;
/// Largest alignment shift between a coefficient and its working exponent (one SFTAC, 16 bits).
inline constexpr int8_t kMaxAlignShift = 16;

inline constexpr uint8_t kCoeffWords = 3;
inline constexpr uint8_t kNormWords = 3;

/// Words of a PolyQ31 of the given degree.
constexpr uint8_t PolyWords(uint8_t degree) {
  return static_cast<uint8_t>(1 + kCoeffWords * (degree + 1));
}

/// Decodes a coefficient from 3 words; kOutOfRange if the exponent is outside the accepted range.
ConstantsStatus CoeffFromWords(const int16_t* words, CoeffQ31* coeff);
void CoeffToWords(const CoeffQ31& coeff, int16_t* words);

/// Decodes a normalisation; kOutOfRange unless 0 <= shift <= max_shift.
ConstantsStatus NormFromWords(const int16_t* words, uint8_t max_shift, InputNormQ31* norm);
void NormToWords(const InputNormQ31& norm, int16_t* words);

/// Decodes a polynomial of `degree` (coefficients above it are set to zero) and validates it:
/// kOutOfRange for a bad exponent or an alignment shift outside 0..16; kWouldOverflow unless
/// sum_k |c_k| < 2^work_exponent, which guarantees that no Horner partial sum overflows for |x|
/// <= 1.
ConstantsStatus PolyFromWords(const int16_t* words, uint8_t degree, PolyQ31* poly);
void PolyToWords(const PolyQ31& poly, uint8_t degree, int16_t* words);

/// kOk if every alignment shift is valid and sum_k |c_k| < 2^work_exponent (see PolyFromWords).
ConstantsStatus ValidatePoly(const PolyQ31& poly, uint8_t degree);

}  // namespace adahrs::firmware_model
