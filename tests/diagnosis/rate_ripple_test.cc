// The table-ripple lock-in against sinusoids written here: amplitudes and phases recovered within
// their stated standard errors, white noise giving chi^2_2 statistics, and the test's size and
// estimate over many draws of segments with a known ripple.
#include "diagnosis/rate_ripple.h"

#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

namespace adahrs::diagnosis {
namespace {

// One segment of rows at 100 Hz: offset, drift, a line of `amplitude` at `f_hz` and white noise.
void Rows(double rate_dps,
          double seconds,
          double amplitude,
          double sigma,
          std::mt19937_64& rng,
          std::vector<double>* t,
          std::vector<double>* y) {
  std::normal_distribution<double> noise(0.0, sigma);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * M_PI);
  const double f_hz = std::abs(rate_dps) / 360.0, p = phase(rng);
  t->clear();
  y->clear();
  for (int i = 0; i < static_cast<int>(seconds * 100.0); ++i) {
    const double ts = 12.0 + 0.01 * i;
    t->push_back(ts);
    y->push_back(4.2e6 + 3.0 * ts + amplitude * std::cos(2.0 * M_PI * f_hz * ts + p) + noise(rng));
  }
}

TEST(RateRipple, LockInRecoversAKnownLineWithinItsStandardError) {
  std::mt19937_64 rng(5);
  int within = 0, n = 200;
  double z2_sum = 0.0;
  for (int i = 0; i < n; ++i) {
    std::vector<double> t, y;
    Rows(150.0, 30.0, 900.0, 6000.0, rng, &t, &y);
    const std::optional<LockIn> l = FitLockIn(t, y, 150.0 / 360.0);
    ASSERT_TRUE(l.has_value());
    const double amp = std::hypot(l->cos_amp, l->sin_amp);
    within += std::abs(amp - 900.0) < 3.0 * l->se;
    // The standard error against the one a white floor gives: sigma sqrt(2 / N).
    EXPECT_NEAR(l->se, 6000.0 * std::sqrt(2.0 / 3000.0), 0.1 * l->se);
    std::vector<double> t0, y0;
    Rows(150.0, 30.0, 0.0, 6000.0, rng, &t0, &y0);
    z2_sum += FitLockIn(t0, y0, 150.0 / 360.0)->Statistic();
  }
  EXPECT_GE(within, 196);
  EXPECT_NEAR(z2_sum / n, 2.0, 0.3);  // chi^2 with 2 degrees of freedom has mean 2
}

TEST(RateRipple, SlowOrShortSegmentsAreNotMeasured) {
  std::mt19937_64 rng(6);
  std::vector<double> t, y;
  Rows(30.0, 60.0, 0.0, 1.0, rng, &t, &y);  // 0.083 Hz
  EXPECT_FALSE(MeasureRipple(0, 30.0, t, y).has_value());
  Rows(150.0, 6.0, 0.0, 1.0, rng, &t, &y);  // 2.5 turns
  EXPECT_FALSE(MeasureRipple(0, 150.0, t, y).has_value());
  Rows(-150.0, 10.0, 0.0, 1.0, rng, &t, &y);
  const std::optional<RippleSegment> s = MeasureRipple(0, -150.0, t, y);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->controls.size(), RippleControlRatios().size());
  const RippleTest none = TestRipple({}, 20971.52, 1e-3, 0.84);
  EXPECT_FALSE(none.testable);
  EXPECT_FALSE(none.note.empty());
}

// 200 draws of six rate segments: without ripple the test rejects at about its level; with a
// ripple of 4e-4 the estimate lies within 3 standard errors of it on at least 95 %.
TEST(RateRipple, TestHoldsItsLevelAndSizesAKnownRipple) {
  std::mt19937_64 rng(7);
  constexpr double kCountsPerDps = 20971.52, kSigma = 6000.0, kAlpha = 0.05;
  int rejected = 0, within = 0, found = 0;
  for (int draw = 0; draw < 200; ++draw) {
    for (const double k : {0.0, 4e-4}) {
      std::vector<RippleSegment> segs;
      for (double rate : {-150.0, -100.0, -50.0, 50.0, 100.0, 150.0}) {
        std::vector<double> t, y;
        Rows(rate, 30.0, k * std::abs(rate) * kCountsPerDps, kSigma, rng, &t, &y);
        segs.push_back(*MeasureRipple(static_cast<int>(segs.size()), rate, t, y));
      }
      const RippleTest r = TestRipple(segs, kCountsPerDps, kAlpha, 0.84);
      ASSERT_TRUE(r.testable);
      if (k == 0.0) {
        rejected += r.p_value < kAlpha;
      } else {
        found += r.p_value < kAlpha;
        within += std::abs(r.ratio - k) <= 3.0 * r.ratio_se;
      }
    }
  }
  std::printf("ripple: size %d of 200 at %.2f; found %d of 200, %d within 3 SE\n",
              rejected,
              kAlpha,
              found,
              within);
  EXPECT_LE(rejected, 20);  // 10 expected; the controls' inflation only makes the test stricter
  EXPECT_GE(within, 190);
  EXPECT_GE(found, 190);
}

}  // namespace
}  // namespace adahrs::diagnosis
