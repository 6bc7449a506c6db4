// Constructed-truth tests of the gyro scale-factor nonlinearity fit (Eq. 23).
#include "calib/solvers/gyro_scale_fit.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/median.h"
#include "common/random.h"

namespace adahrs::calib {
namespace {

using ::testing::HasSubstr;

// Counts per deg/s 20,972 (reference-method.md), null 4.2e6 counts, with a 0.1 % FS cubic bow.
constexpr double kNull_cnt = 4.2e6;
constexpr double kCntPerDps = 20972.0;
double Counts(double rate_dps) {
  const double x = rate_dps / 150.0;
  return kNull_cnt + kCntPerDps * (rate_dps + 0.15 * (x * x * x - x));
}

std::vector<GyroRateMean> Steps(common::Rng* rng, double noise_cnt) {
  std::vector<GyroRateMean> steps;
  for (double r : {-150.0, -100.0, -50.0, 0.0, 50.0, 100.0, 150.0}) {
    const double e = rng ? noise_cnt * rng->Normal() : 0.0;
    steps.push_back({r, Counts(r) + (r == 0.0 ? 0.0 : e), noise_cnt});
  }
  return steps;
}

TEST(GyroScaleFit, RecoversTheCubicMapping) {
  const GyroScaleEstimate e = FitGyroScale("gx", Steps(nullptr, 1.0));
  EXPECT_EQ(e.fit.null_cnt, kNull_cnt);
  // l1 ~ 1 / 20,972 deg/s per count with the bow's linear part: 1 / (20,972 (1 - 0.001)).
  EXPECT_NEAR(e.fit.l[1], 1.0 / (kCntPerDps * (1.0 - 0.15 / 150.0)), 1e-8);
  // The inverse of a cubic is not a cubic: on the seven rates the fit reproduces the reference
  // rates to the inverse's 5th-order remainder, ~ (0.1 %)^2 * 150 deg/s ~ 2e-4 deg/s.
  for (double r : {-150.0, -50.0, 100.0}) {
    const double d = Counts(r) - kNull_cnt;
    const auto& l = e.fit.l;
    EXPECT_NEAR(l[0] + l[1] * d + l[2] * d * d + l[3] * d * d * d, r, 1e-3) << r;
  }
  EXPECT_EQ(e.rates, 7);
}

// Noisy means, 3 residual dof: the slope's standardised error has unit spread (t with 3 dof, sd
// sqrt(3) = 1.73; we check the median |z| instead, 0.765 for t3, within 0.6..0.95 over 300 sets:
// > 3 sigma of the median's sampling error ~ 0.05).
TEST(GyroScaleFit, StandardErrorsFollowTheResiduals) {
  common::Rng rng(41);
  std::vector<double> abs_z;
  for (int k = 0; k < 300; ++k) {
    const GyroScaleEstimate e = FitGyroScale("gy", Steps(&rng, 300.0));
    const GyroScaleEstimate exact = FitGyroScale("gy", Steps(nullptr, 1.0));
    abs_z.push_back(std::abs(e.fit.l[1] - exact.fit.l[1]) / e.l_se[1]);
  }
  const double median_abs_z = common::Median(abs_z);
  EXPECT_GT(median_abs_z, 0.6);
  EXPECT_LT(median_abs_z, 0.95);
}

TEST(GyroScaleFit, RefusesTooFewRates) {
  auto steps = Steps(nullptr, 1.0);
  steps.erase(steps.begin() + 5, steps.end());  // -150 -100 -50 0 50: five rates, still enough
  EXPECT_NO_THROW(FitGyroScale("gz", steps));
  steps.pop_back();
  EXPECT_THAT([&] { FitGyroScale("gz", steps); },
              ::testing::ThrowsMessage<DegenerateDesignError>(HasSubstr(
                  "gyro scale fit of gz: design refused: 4 distinct rates, at least 5 are "
                  "needed (too few rates)")));
}

TEST(GyroScaleFit, RefusesWithoutZeroRate) {
  auto steps = Steps(nullptr, 1.0);
  steps.erase(steps.begin() + 3);
  EXPECT_THAT([&] { FitGyroScale("gx", steps); },
              ::testing::ThrowsMessage<DegenerateDesignError>(
                  HasSubstr("no 0 deg/s step to normalise the means by")));
}

// The table still settling for part of the null acquisition reports a mean of -1e-5 deg/s (a
// fresh-clone demo's IMU-0001 gy): that step is the null step, not a missing one.
TEST(GyroScaleFit, NullStepIsTheOneReportedWithinTheToleranceOfZero) {
  auto steps = Steps(nullptr, 1.0);
  steps[3].rate_dps = -9.6e-6;
  const GyroScaleEstimate e = FitGyroScale("gy", steps);
  EXPECT_EQ(e.fit.null_cnt, steps[3].t_cnt);
  steps[3].rate_dps = 2.0 * kNullStepTolerance_dps;
  EXPECT_THAT([&] { FitGyroScale("gy", steps); },
              ::testing::ThrowsMessage<DegenerateDesignError>(HasSubstr("no 0 deg/s step")));
}

}  // namespace
}  // namespace adahrs::calib
