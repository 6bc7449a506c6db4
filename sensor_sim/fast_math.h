// Inline replacements for the libm calls on the sensors' 100 Hz hot path (on the baseline x86-64
// target, built without -march, std::floor, std::llround and std::exp are out-of-line calls that
// also spill every live floating-point register):
//   FloorToInt64(x)          == (int64_t)std::floor(x)   exactly, for |x| < 2^62
//   RoundHalfAwayToInt64(x)  == std::llround(x)          exactly, for |x| < 2^62
//   RoundHalfEven(x)         == std::nearbyint(x)        exactly, for |x| < 2^51, default rounding
//   BoundedExp(x)            ≈ std::exp(x) within 1 ulp, for |x| <= kBoundedExpMaxArg (Tang's
//                            table method, ACM TOMS 15(2), 1989)
// Units: none (pure arithmetic).
// Why they are exact, the error budget of BoundedExp: docs/performance.md ("Sensor physics",
// the fast_math.h item).
// Left out: special cases (arguments outside the ranges are the caller's to exclude; NaN,
// infinities or |x| >= 2^50 make the float-to-integer conversion undefined).
#pragma once

#include <bit>
#include <cstdint>

namespace adahrs::sensor_sim {

/// floor(x) as an integer, exact for |x| < 2^62.
inline int64_t FloorToInt64(double x) {
  const auto truncated = static_cast<int64_t>(x);  // toward zero
  return truncated - (static_cast<double>(truncated) > x ? 1 : 0);
}

/// Nearest integer, halves away from zero (std::llround), exact for |x| < 2^62.
inline int64_t RoundHalfAwayToInt64(double x) {
  const auto truncated = static_cast<int64_t>(x);              // toward zero
  const double fraction = x - static_cast<double>(truncated);  // exact, same sign as x
  return truncated + (fraction >= 0.5 ? 1 : 0) - (fraction <= -0.5 ? 1 : 0);
}

namespace fast_math_internal {
// Adding 1.5·2^52 leaves round-to-nearest-even(y) in the low mantissa bits for |y| < 2^51.
inline constexpr double kRoundShift = 0x1.8p52;
}  // namespace fast_math_internal

/// Nearest integer, halves to even (std::nearbyint in the default rounding mode), as a double,
/// exact for |x| < 2^51. (The compiler may not fold (x + c) − c: we build without -ffast-math.)
inline double RoundHalfEven(double x) {
  return (x + fast_math_internal::kRoundShift) - fast_math_internal::kRoundShift;
}

/// |x| up to which BoundedExp is accurate: the result stays a normal double (e^±708 is near the
/// limits) with margin.
inline constexpr double kBoundedExpMaxArg = 700.0;

namespace fast_math_internal {

inline constexpr int kExpTableBits = 6;
inline constexpr int kExpTableSize = 1 << kExpTableBits;

// 2^(j/64), j = 0..63, correctly rounded. Generated with Python's exact decimal arithmetic:
//   getcontext().prec = 60; float(Decimal(2) ** (Decimal(j) / 64)).hex()
inline constexpr double kExp2Table[kExpTableSize] = {
    0x1.0000000000000p+0, 0x1.02c9a3e778061p+0, 0x1.059b0d3158574p+0, 0x1.0874518759bc8p+0,
    0x1.0b5586cf9890fp+0, 0x1.0e3ec32d3d1a2p+0, 0x1.11301d0125b51p+0, 0x1.1429aaea92de0p+0,
    0x1.172b83c7d517bp+0, 0x1.1a35beb6fcb75p+0, 0x1.1d4873168b9aap+0, 0x1.2063b88628cd6p+0,
    0x1.2387a6e756238p+0, 0x1.26b4565e27cddp+0, 0x1.29e9df51fdee1p+0, 0x1.2d285a6e4030bp+0,
    0x1.306fe0a31b715p+0, 0x1.33c08b26416ffp+0, 0x1.371a7373aa9cbp+0, 0x1.3a7db34e59ff7p+0,
    0x1.3dea64c123422p+0, 0x1.4160a21f72e2ap+0, 0x1.44e086061892dp+0, 0x1.486a2b5c13cd0p+0,
    0x1.4bfdad5362a27p+0, 0x1.4f9b2769d2ca7p+0, 0x1.5342b569d4f82p+0, 0x1.56f4736b527dap+0,
    0x1.5ab07dd485429p+0, 0x1.5e76f15ad2148p+0, 0x1.6247eb03a5585p+0, 0x1.6623882552225p+0,
    0x1.6a09e667f3bcdp+0, 0x1.6dfb23c651a2fp+0, 0x1.71f75e8ec5f74p+0, 0x1.75feb564267c9p+0,
    0x1.7a11473eb0187p+0, 0x1.7e2f336cf4e62p+0, 0x1.82589994cce13p+0, 0x1.868d99b4492edp+0,
    0x1.8ace5422aa0dbp+0, 0x1.8f1ae99157736p+0, 0x1.93737b0cdc5e5p+0, 0x1.97d829fde4e50p+0,
    0x1.9c49182a3f090p+0, 0x1.a0c667b5de565p+0, 0x1.a5503b23e255dp+0, 0x1.a9e6b5579fdbfp+0,
    0x1.ae89f995ad3adp+0, 0x1.b33a2b84f15fbp+0, 0x1.b7f76f2fb5e47p+0, 0x1.bcc1e904bc1d2p+0,
    0x1.c199bdd85529cp+0, 0x1.c67f12e57d14bp+0, 0x1.cb720dcef9069p+0, 0x1.d072d4a07897cp+0,
    0x1.d5818dcfba487p+0, 0x1.da9e603db3285p+0, 0x1.dfc97337b9b5fp+0, 0x1.e502ee78b3ff6p+0,
    0x1.ea4afa2a490dap+0, 0x1.efa1bee615a27p+0, 0x1.f50765b6e4540p+0, 0x1.fa7c1819e90d8p+0,
};

inline constexpr double kSixtyFourOverLn2 = 0x1.71547652b82fep+6;  // 64/ln2
inline constexpr double kLn2Over64Head = 0x1.62e42fefa0000p-7;     // ln2/64, top 36 bits
inline constexpr double kLn2Over64Tail = 0x1.cf79abc9e3b3ap-46;    // ln2/64 − head
}  // namespace fast_math_internal

/// e^x within 1 ulp for |x| ≤ kBoundedExpMaxArg (see the file comment).
inline double BoundedExp(double x) {
  using namespace fast_math_internal;
  const double k_shifted = x * kSixtyFourOverLn2 + kRoundShift;
  const double k = k_shifted - kRoundShift;  // round(64·x/ln2), an exact integer
  const auto k_int = static_cast<int64_t>(k);
  const double r = (x - k * kLn2Over64Head) - k * kLn2Over64Tail;
  // e^r − 1 = r + r²/2 + r³/6 + r⁴/24 + r⁵/120 (Horner).
  const double q = r + r * r * (1.0 / 2 + r * (1.0 / 6 + r * (1.0 / 24 + r * (1.0 / 120))));
  const double table = kExp2Table[k_int & (kExpTableSize - 1)];
  // 2^(k div 64) (arithmetic shift: floor division) placed in the exponent field.
  const double power_of_two =
      std::bit_cast<double>(static_cast<uint64_t>((k_int >> kExpTableBits) + 1023) << 52);
  return power_of_two * (table + table * q);
}

}  // namespace adahrs::sensor_sim
