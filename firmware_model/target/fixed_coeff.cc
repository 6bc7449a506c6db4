#include "firmware_model/target/fixed_coeff.h"

namespace adahrs::firmware_model {
namespace {

int32_t Join32(int16_t hi, int16_t lo) {
  const uint32_t bits = (static_cast<uint32_t>(static_cast<uint16_t>(hi)) << 16) |
                        static_cast<uint32_t>(static_cast<uint16_t>(lo));
  return static_cast<int32_t>(bits);
}

int16_t High16(int32_t v) { return static_cast<int16_t>(static_cast<uint32_t>(v) >> 16); }
int16_t Low16(int32_t v) { return static_cast<int16_t>(static_cast<uint32_t>(v) & 0xFFFFu); }

int64_t Abs64(int32_t v) { return v < 0 ? -static_cast<int64_t>(v) : static_cast<int64_t>(v); }

}  // namespace

ConstantsStatus CoeffFromWords(const int16_t* words, CoeffQ31* coeff) {
  if (words[2] < kMinExponent || words[2] > kMaxExponent) return ConstantsStatus::kOutOfRange;
  coeff->mantissa_q31 = Join32(words[0], words[1]);
  coeff->exponent = static_cast<int8_t>(words[2]);
  return ConstantsStatus::kOk;
}

void CoeffToWords(const CoeffQ31& coeff, int16_t* words) {
  words[0] = High16(coeff.mantissa_q31);
  words[1] = Low16(coeff.mantissa_q31);
  words[2] = coeff.exponent;
}

ConstantsStatus NormFromWords(const int16_t* words, uint8_t max_shift, InputNormQ31* norm) {
  if (words[2] < 0 || words[2] > max_shift) return ConstantsStatus::kOutOfRange;
  norm->centre = Join32(words[0], words[1]);
  norm->shift = static_cast<uint8_t>(words[2]);
  return ConstantsStatus::kOk;
}

void NormToWords(const InputNormQ31& norm, int16_t* words) {
  words[0] = High16(norm.centre);
  words[1] = Low16(norm.centre);
  words[2] = norm.shift;
}

ConstantsStatus ValidatePoly(const PolyQ31& poly, uint8_t degree) {
  if (degree > kMaxPolyDegree || poly.work_exponent < kMinExponent ||
      poly.work_exponent > kMaxExponent) {
    return ConstantsStatus::kOutOfRange;
  }
  // sum_k |m_k| 2^(e_k - E) < 2^31, accumulated in units of 2^-16 of a Q31 LSB so that every
  // alignment shift (0..16) is exact; the bound then also covers the Horner partial sums.
  int64_t sum_abs = 0;
  for (uint8_t k = 0; k <= degree; ++k) {
    const int32_t align = poly.work_exponent - poly.coeff[k].exponent;
    if (align < 0 || align > kMaxAlignShift) return ConstantsStatus::kOutOfRange;
    sum_abs += Abs64(poly.coeff[k].mantissa_q31) << (kMaxAlignShift - align);
  }
  if (sum_abs >= (static_cast<int64_t>(1) << (31 + kMaxAlignShift))) {
    return ConstantsStatus::kWouldOverflow;
  }
  return ConstantsStatus::kOk;
}

ConstantsStatus PolyFromWords(const int16_t* words, uint8_t degree, PolyQ31* poly) {
  if (degree > kMaxPolyDegree) return ConstantsStatus::kOutOfRange;
  if (words[0] < kMinExponent || words[0] > kMaxExponent) return ConstantsStatus::kOutOfRange;
  PolyQ31 decoded{};
  decoded.work_exponent = static_cast<int8_t>(words[0]);
  for (uint8_t k = 0; k <= kMaxPolyDegree; ++k) {
    decoded.coeff[k] = CoeffQ31{0, decoded.work_exponent};
  }
  for (uint8_t k = 0; k <= degree; ++k) {
    const ConstantsStatus status = CoeffFromWords(words + 1 + kCoeffWords * k, &decoded.coeff[k]);
    if (status != ConstantsStatus::kOk) return status;
  }
  const ConstantsStatus status = ValidatePoly(decoded, degree);
  if (status != ConstantsStatus::kOk) return status;
  *poly = decoded;
  return ConstantsStatus::kOk;
}

void PolyToWords(const PolyQ31& poly, uint8_t degree, int16_t* words) {
  words[0] = poly.work_exponent;
  for (uint8_t k = 0; k <= degree; ++k) CoeffToWords(poly.coeff[k], words + 1 + kCoeffWords * k);
}

}  // namespace adahrs::firmware_model
