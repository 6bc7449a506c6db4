#include "sensor_sim/double_pair.h"

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

// The pair functions against the C library, lane by lane, with different values in the two lanes
// (a swapped or shared lane shows up as a mismatch).

TEST(DoublePair, FloorPairIsStdFloorInBothLanes) {
  std::vector<double> x;
  for (double base : {0.0, 0.5, 1.0, 2.5, 1e6 + 0.5, 0x1p50, 0x1p50 + 0.5}) {
    for (double s : {1.0, -1.0}) {
      x.push_back(s * base);
      x.push_back(std::nextafter(s * base, std::numeric_limits<double>::infinity()));
      x.push_back(std::nextafter(s * base, -std::numeric_limits<double>::infinity()));
    }
  }
  common::Rng rng(41);
  for (int i = 0; i < 100000; ++i) x.push_back(rng.Uniform(-4e5, 4e5));
  for (size_t i = 0; i + 1 < x.size(); ++i) {
    const DoublePair floor = FloorPair(DoublePair{x[i], x[i + 1]});
    ASSERT_EQ(floor[0], std::floor(x[i])) << x[i];
    ASSERT_EQ(floor[1], std::floor(x[i + 1])) << x[i + 1];
  }
}

TEST(DoublePair, SqrtPairIsStdSqrtInBothLanes) {
  common::Rng rng(42);
  for (int i = 0; i < 100000; ++i) {
    const double a = rng.Uniform(0.0, 1.0), b = rng.Uniform(0.0, 1e6);
    const DoublePair root = SqrtPair(DoublePair{a, b});
    ASSERT_EQ(root[0], std::sqrt(a));
    ASSERT_EQ(root[1], std::sqrt(b));
  }
}

// Within 1 ulp of std::exp over the range the ADXL210E uses it on (−Δ/τ down to −700) and the
// positive side, as BoundedExp itself (fast_math_test).
TEST(DoublePair, BoundedExpPairWithinOneUlpOfStdExp) {
  common::Rng rng(43);
  auto ulps = [](double a, double b) {
    const auto ia = std::bit_cast<int64_t>(a), ib = std::bit_cast<int64_t>(b);
    return ia > ib ? ia - ib : ib - ia;
  };
  for (int i = 0; i < 200000; ++i) {
    const double a = rng.Uniform(-kBoundedExpMaxArg, kBoundedExpMaxArg);
    const double b = rng.Uniform(-5.0, 0.0);
    const DoublePair e = BoundedExpPair(DoublePair{a, b});
    ASSERT_LE(ulps(e[0], std::exp(a)), 1) << a;
    ASSERT_LE(ulps(e[1], std::exp(b)), 1) << b;
  }
}

TEST(DoublePair, ClampPairIsStdClampInBothLanes) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double a : {-0.5, 0.0, 0.25, 1.0, 1.5}) {
    for (double b : {-2.0, 0.75, 3.0}) {
      const DoublePair c = ClampPair(DoublePair{a, b}, 0.0, 1.0);
      EXPECT_EQ(c[0], std::clamp(a, 0.0, 1.0));
      EXPECT_EQ(c[1], std::clamp(b, 0.0, 1.0));
    }
  }
  EXPECT_TRUE(std::isnan(ClampPair(DoublePair{nan, 0.5}, 0.0, 1.0)[0]));
}

}  // namespace
}  // namespace adahrs::sensor_sim
