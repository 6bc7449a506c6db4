#include "sensor_sim/fast_math.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "common/random.h"

namespace adahrs::sensor_sim {
namespace {

// Distance in units in the last place between two finite positive doubles (their bit patterns
// are ordered like their values).
int64_t UlpDistance(double a, double b) {
  const auto ia = std::bit_cast<int64_t>(a);
  const auto ib = std::bit_cast<int64_t>(b);
  return ia > ib ? ia - ib : ib - ia;
}

// Arguments that stress rounding: halves, their neighbours, integers, values near 2^52 and 2^62
// (where every double is an integer), and signed zeros.
std::vector<double> EdgeCases() {
  std::vector<double> v;
  for (double base : {0.0,
                      0.5,
                      1.0,
                      1.5,
                      2.5,
                      3.0,
                      1e6 + 0.5,
                      0x1p52,
                      0x1p52 + 1.0,
                      0x1p61,
                      0.49999999999999994,
                      4503599627370495.5}) {
    for (double s : {1.0, -1.0}) {
      const double x = s * base;
      v.push_back(x);
      v.push_back(std::nextafter(x, std::numeric_limits<double>::infinity()));
      v.push_back(std::nextafter(x, -std::numeric_limits<double>::infinity()));
    }
  }
  return v;
}

TEST(FastMath, FloorToInt64MatchesStdFloor) {
  for (double x : EdgeCases()) {
    EXPECT_EQ(FloorToInt64(x), static_cast<int64_t>(std::floor(x))) << std::hexfloat << x;
  }
  common::Rng rng(11);
  for (int i = 0; i < 1000000; ++i) {
    // Magnitudes spread over 0 … 2^40 so every fraction length occurs.
    const double x = (rng.Uniform() - 0.5) * std::ldexp(1.0, static_cast<int>(rng.Uniform() * 40));
    ASSERT_EQ(FloorToInt64(x), static_cast<int64_t>(std::floor(x))) << std::hexfloat << x;
  }
}

TEST(FastMath, RoundHalfAwayToInt64MatchesLlround) {
  for (double x : EdgeCases()) {
    EXPECT_EQ(RoundHalfAwayToInt64(x), std::llround(x)) << std::hexfloat << x;
  }
  common::Rng rng(12);
  for (int i = 0; i < 1000000; ++i) {
    const double x = (rng.Uniform() - 0.5) * std::ldexp(1.0, static_cast<int>(rng.Uniform() * 40));
    ASSERT_EQ(RoundHalfAwayToInt64(x), std::llround(x)) << std::hexfloat << x;
    // Exact halves, where llround's rule (away from zero) differs from nearbyint's (to even).
    const double half = std::floor(x) + 0.5;
    ASSERT_EQ(RoundHalfAwayToInt64(half), std::llround(half)) << std::hexfloat << half;
  }
}

TEST(FastMath, RoundHalfEvenMatchesNearbyint) {
  for (double x : EdgeCases()) {
    if (std::fabs(x) >= 0x1p51) continue;  // outside the documented range
    EXPECT_EQ(RoundHalfEven(x), std::nearbyint(x)) << std::hexfloat << x;
  }
  common::Rng rng(14);
  for (int i = 0; i < 1000000; ++i) {
    const double x = (rng.Uniform() - 0.5) * std::ldexp(1.0, static_cast<int>(rng.Uniform() * 40));
    ASSERT_EQ(RoundHalfEven(x), std::nearbyint(x)) << std::hexfloat << x;
    const double half = std::floor(x) + 0.5;  // ties: to even, unlike llround
    ASSERT_EQ(RoundHalfEven(half), std::nearbyint(half)) << std::hexfloat << half;
  }
}

// glibc's exp is within 1 ulp of e^x (its documented bound; in practice correctly rounded almost
// always) and BoundedExp's own error bound is < 1 ulp (fast_math.h), so the two may differ by at
// most 2 ulp anywhere; we require that, and that they agree to 1 ulp in more than 99.9 % of a dense
// sweep (a wrong table entry or coefficient shows up as errors of many ulp, or everywhere).
TEST(FastMath, BoundedExpWithinOneUlpOfStdExpOverItsRange) {
  constexpr int kSweep = 2000001;
  int64_t worst_ulp = 0;
  int beyond_one_ulp = 0;
  for (int i = 0; i < kSweep; ++i) {
    const double x = -kBoundedExpMaxArg + 2.0 * kBoundedExpMaxArg * i / (kSweep - 1);
    const int64_t ulp = UlpDistance(BoundedExp(x), std::exp(x));
    worst_ulp = std::max(worst_ulp, ulp);
    if (ulp > 1) ++beyond_one_ulp;
  }
  // The range the sensors use most, [−10, 0], sampled finely and at random points.
  common::Rng rng(13);
  for (int i = 0; i < kSweep; ++i) {
    const double x = -10.0 * rng.Uniform();
    const int64_t ulp = UlpDistance(BoundedExp(x), std::exp(x));
    worst_ulp = std::max(worst_ulp, ulp);
    if (ulp > 1) ++beyond_one_ulp;
  }
  EXPECT_LE(worst_ulp, 2);
  EXPECT_LT(beyond_one_ulp, 2 * kSweep / 1000);
  // Exact points: e^0 = 1, and table nodes x = j·ln2/64 land on 2^(j/64).
  EXPECT_EQ(BoundedExp(0.0), 1.0);
  EXPECT_EQ(BoundedExp(-0.0), 1.0);
  for (int j = -64; j <= 64; ++j) {
    const double x = j * std::log(2.0) / 64.0;
    EXPECT_LE(UlpDistance(BoundedExp(x), std::exp2(j / 64.0)), 1) << j;
  }
}

}  // namespace
}  // namespace adahrs::sensor_sim
