#include "common/allan.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/random.h"
#include "common/units.h"
#include "tests/support/error_text.h"

namespace adahrs::common {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

std::vector<double> WhiteNoise(size_t n, double sigma, uint64_t seed) {
  Rng rng(seed);
  std::vector<double> x(n);
  for (double& v : x) v = sigma * rng.Normal();
  return x;
}

std::string ErrorOf(const std::function<void()>& f) {
  return test_support::ErrorText<std::invalid_argument>(f);
}

// Discrete white noise of variance s^2 has AVAR(m) = s^2 / m exactly (in expectation).
TEST(Allan, WhiteNoiseFallsAsOneOverSqrtTau) {
  constexpr double kSigma = 2.0;
  constexpr double kDt_s = 0.01;
  const std::vector<double> x = WhiteNoise(200000, kSigma, 11);
  for (size_t m : {1u, 10u, 100u, 1000u}) {
    const AllanPoint p = OverlappingAllanDeviationAt(x, kDt_s, m);
    const double expected = kSigma / std::sqrt(static_cast<double>(m));
    EXPECT_DOUBLE_EQ(p.tau_s, m * kDt_s);
    // relative_error is the non-overlapping 1-sigma error, an upper bound for the overlapping
    // estimator: 4 of them is a > 4-sigma band.
    EXPECT_NEAR(p.adev, expected, 4.0 * p.relative_error * expected) << "m = " << m;
  }
}

// A linear ramp y = k t: adjacent cluster means differ by k tau, so AVAR = (k tau)^2 / 2 exactly.
TEST(Allan, RampGivesExactValue) {
  constexpr double kSlope = 0.3;
  constexpr double kDt_s = 0.5;
  std::vector<double> x(1000);
  for (size_t i = 0; i < x.size(); ++i) x[i] = kSlope * kDt_s * static_cast<double>(i);
  for (size_t m : {1u, 7u, 100u}) {
    const double tau_s = m * kDt_s;
    EXPECT_NEAR(OverlappingAllanDeviationAt(x, kDt_s, m).adev,
                kSlope * tau_s / std::sqrt(2.0),
                1e-9 * kSlope * tau_s);
  }
}

TEST(Allan, CurveIsLogSpacedAndStopsAtTenthOfRecord) {
  const std::vector<double> x = WhiteNoise(10000, 1.0, 3);
  const std::vector<AllanPoint> curve = OverlappingAllanDeviation(x, 0.01, 5);
  ASSERT_FALSE(curve.empty());
  EXPECT_EQ(curve.front().cluster_size, 1u);
  EXPECT_EQ(curve.back().cluster_size, 1000u);  // 10^3 = N/10 with 5 points per decade
  for (size_t i = 1; i < curve.size(); ++i) {
    EXPECT_GT(curve[i].cluster_size, curve[i - 1].cluster_size);
  }
}

// The convention of allan.h: white noise of one-sided density N, sampled as averages over dt,
// has per-sample variance N^2 / (2 dt), one-sided PSD N^2, Allan deviation N / sqrt(2 tau).
TEST(Allan, WelchAndAllanAgreeOnOneSidedDensityConvention) {
  constexpr double kDensity = 0.05;  // unit/sqrt(Hz), one-sided
  constexpr double kDt_s = 0.01;
  const std::vector<double> x = WhiteNoise(400000, kDensity / std::sqrt(2.0 * kDt_s), 5);
  // 4096-sample segments, 195 segments with 50 % overlap; over 0..5 Hz 204 bins are averaged, so
  // the relative standard error is ~1/sqrt(195 · 204 · 0.5) < 1 %; 4 % is a > 4-sigma band.
  EXPECT_NEAR(
      LowFrequencyPsd(x, kDt_s, 4096, 5.0), kDensity * kDensity, 0.04 * kDensity * kDensity);
  const AllanPoint p = OverlappingAllanDeviationAt(x, kDt_s, 100);
  const double expected = kDensity / std::sqrt(2.0 * p.tau_s);
  EXPECT_NEAR(p.adev, expected, 4.0 * p.relative_error * expected);
}

// Parseval: the one-sided PSD integrates to the variance; for a sinusoid of amplitude A that is
// A^2 / 2. The Hann window spreads the line over 3 bins but keeps the total (normalised by sum
// w^2).
TEST(Allan, WelchIntegratesToSinusoidPower) {
  constexpr double kAmplitude = 3.0;
  constexpr double kDt_s = 0.001;
  constexpr double kF_hz = 37.3;
  std::vector<double> x(1 << 16);
  for (size_t i = 0; i < x.size(); ++i) {
    x[i] = kAmplitude * std::sin(2.0 * kPi * kF_hz * kDt_s * static_cast<double>(i));
  }
  const std::vector<PsdPoint> psd = WelchPsd(x, kDt_s, 2048);
  const double df_hz = psd[1].f_hz - psd[0].f_hz;
  double power = 0.0;
  for (const PsdPoint& p : psd) power += p.psd * df_hz;
  // 37.3 Hz is between bins; a Hann window's scalloping does not change the integrated power of a
  // line beyond ~0.5 % (its sidelobes hold < 0.05 %), hence 1 %.
  EXPECT_NEAR(power, kAmplitude * kAmplitude / 2.0, 0.01 * kAmplitude * kAmplitude / 2.0);
}

TEST(Allan, BadArgumentsAreRefusedWithValues) {
  const std::vector<double> x(100, 1.0);
  EXPECT_THAT(ErrorOf([&] { OverlappingAllanDeviationAt(x, 0.0, 1); }),
              AllOf(HasSubstr("dt_s"), HasSubstr("got 0")));
  EXPECT_THAT(ErrorOf([&] { OverlappingAllanDeviationAt(x, 0.01, 50); }),
              AllOf(HasSubstr("cluster size 50"), HasSubstr("N = 100")));
  EXPECT_THAT(ErrorOf([&] { WelchPsd(x, 0.01, 48); }), HasSubstr("power of two >= 8, got 48"));
  EXPECT_THAT(ErrorOf([&] { WelchPsd(x, 0.01, 128); }), HasSubstr("shorter than one segment"));
  EXPECT_THAT(ErrorOf([&] { LowFrequencyPsd(x, 0.01, 64, 0.5); }),
              HasSubstr("no bin below f_max_hz"));
}

}  // namespace
}  // namespace adahrs::common
