// The gyro wander's restricted-likelihood estimate (calib/imu_calibration/gyro_wander_fit.h) on
// data drawn from a known covariance: 240 one-minute windows over 8 h of one run, a bias and a
// thermal slope as the model, white variances D and the flicker model K(B, c) of
// gyro_bias_covariance.h with a known floor and time scale.
#include "calib/imu_calibration/gyro_wander_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "calib/imu_calibration/gyro_bias_covariance.h"

namespace adahrs::calib {
namespace {

constexpr double kCountsPerDps = 20971.52, kFrame_s = 0.01, kPriorFloor_dph = 75.0;

struct Problem {
  std::vector<ImuObservation> obs;
  Eigen::MatrixXd design;
  Eigen::VectorXd y, white;
};

Problem Draw(double floor_dph, double time_scale, double white_scale, uint64_t seed) {
  constexpr int kWindows = 240;
  Problem p;
  p.design.resize(kWindows, 2);
  p.white = Eigen::VectorXd::Constant(kWindows, 1.0e6);  // (1,000 counts)^2 per window mean
  for (int i = 0; i < kWindows; ++i) {
    ImuObservation o;
    o.count = 6000;
    o.windows = {{120.0 * i, 120.0 * i + 60.0 - kFrame_s, 6000}};
    p.obs.push_back(o);
    p.design.row(i) << 1.0, std::sin(i / 30.0);
  }
  const Eigen::MatrixXd v =
      Eigen::MatrixXd(p.white.asDiagonal()) * white_scale +
      GyroBiasCovariance_dps2(p.obs, floor_dph / 3600.0, kFrame_s, time_scale) * kCountsPerDps *
          kCountsPerDps;
  const Eigen::LLT<Eigen::MatrixXd> llt(v);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::VectorXd z(kWindows);
  for (int i = 0; i < kWindows; ++i) z[i] = normal(rng);
  p.y = p.design * Eigen::Vector2d(1000.0, 50.0) + llt.matrixL() * z;
  return p;
}

GyroWanderEstimate Estimate(const Problem& p) {
  return EstimateGyroWander(
      p.obs, p.design, p.y, p.white, kPriorFloor_dph, kCountsPerDps, kFrame_s);
}

// A floor three times the prior's is found within a factor of 1.6 on most draws, and the
// likelihood gained over the prior is finite and positive.
TEST(GyroWanderFit, FindsAFloorThreeTimesThePriors) {
  int close = 0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    const GyroWanderEstimate e = Estimate(Draw(3.0 * kPriorFloor_dph, 1.0, 1.0, seed));
    EXPECT_TRUE(std::isfinite(e.log_likelihood_gain)) << seed;
    EXPECT_GT(e.log_likelihood_gain, 0.0) << seed;
    close += std::abs(std::log(e.floor_dph / (3.0 * kPriorFloor_dph))) < std::log(1.6) ? 1 : 0;
  }
  EXPECT_GE(close, 7);
}

// The prior (B0, c = 1, s = 1) is on the grid: the gain is never negative, and the covariance is
// K plus the white excess on its diagonal.
TEST(GyroWanderFit, NeverFitsWorseThanThePriorAndCarriesTheWhiteExcess) {
  const Problem p = Draw(kPriorFloor_dph, 1.0, 2.0, 7);
  const GyroWanderEstimate e = Estimate(p);
  EXPECT_GE(e.log_likelihood_gain, 0.0);
  EXPECT_GT(e.white_scale, 1.0);
  const Eigen::MatrixXd k =
      GyroBiasCovariance_dps2(p.obs, e.floor_dph / 3600.0, kFrame_s, e.time_scale) * kCountsPerDps *
      kCountsPerDps;
  EXPECT_NEAR(e.covariance_cnt2(3, 7), k(3, 7), 1e-9 * std::abs(k(3, 7)));
  EXPECT_NEAR(
      e.covariance_cnt2(5, 5), k(5, 5) + (e.white_scale - 1.0) * p.white[5], 1e-6 * k(5, 5));
}

}  // namespace
}  // namespace adahrs::calib
