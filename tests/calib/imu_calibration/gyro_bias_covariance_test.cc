// The analytic covariance of window means of the gyro bias-instability process against the
// process itself: many realisations of sensor_sim::GyroBiasProcess (its own draws and update
// schedule), their window means, and the sample covariance, within its statistical limits.
#include "calib/imu_calibration/gyro_bias_covariance.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "sensor_sim/gyro_bias_process.h"

namespace adahrs::calib {
namespace {

constexpr double kFrame_s = 0.01;
constexpr double kFloor_dps = 75.0 / 3600.0;

// An observation whose rows are the frames [first, last] of each range, in run `run`.
ImuObservation Observation(std::vector<std::pair<int, int>> frames, int run = 0) {
  ImuObservation o;
  o.run = run;
  for (const auto& [first, last] : frames) {
    o.windows.push_back({first * kFrame_s, last * kFrame_s, last - first + 1});
    o.count += last - first + 1;
  }
  return o;
}

TEST(GyroBiasCovariance, MatchesTheSimulatedProcessWithinItsSamplingError) {
  // Short and long windows, overlapping, nested, near and far apart, and a band revisited.
  const std::vector<ImuObservation> obs = {
      Observation({{0, 299}}),
      Observation({{100, 199}}),
      Observation({{350, 649}}),
      Observation({{6000, 65999}}),
      Observation({{150000, 150299}}),
      Observation({{2000, 2099}, {120000, 120099}}),
  };
  const Eigen::MatrixXd analytic = GyroBiasCovariance_dps2(obs, kFloor_dps, kFrame_s);
  const int n = static_cast<int>(obs.size());
  constexpr int kRealisations = 4000;
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(n, n);
  std::vector<double> frame_bias(150300);
  for (int r = 0; r < kRealisations; ++r) {
    sensor_sim::GyroBiasProcess process(kFloor_dps, true, 0.0, false, kFrame_s, 1000 + r);
    for (double& b : frame_bias) b = process.Step();
    Eigen::VectorXd mean = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) {
      for (const TimeWindow& w : obs[i].windows) {
        const int first = static_cast<int>(std::lround(w.first_s / kFrame_s));
        for (int k = first; k < first + w.rows; ++k) mean[i] += frame_bias[k];
      }
      mean[i] /= obs[i].count;
    }
    sum += mean * mean.transpose();  // the process has zero mean
  }
  const Eigen::MatrixXd sample = sum / kRealisations;
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j) {
      // Standard error of a sample covariance of Gaussian variables with known zero mean.
      const double se = std::sqrt(
          (analytic(i, i) * analytic(j, j) + analytic(i, j) * analytic(i, j)) / kRealisations);
      EXPECT_NEAR(sample(i, j), analytic(i, j), 4.0 * se) << "observations " << i << ", " << j;
    }
  }
  // Sanity of the magnitudes: a 3 s mean keeps nearly the whole variance of the slow poles
  // (4 q^2 less most of the 5 s pole), a 10-minute mean much less of the fast ones.
  const double q = sensor_sim::GyroBiasProcess::PoleSigmaForFloor(kFloor_dps);
  EXPECT_GT(analytic(0, 0), 2.0 * q * q);
  EXPECT_LT(analytic(0, 0), 4.0 * q * q);
  EXPECT_LT(analytic(3, 3), analytic(0, 0));
}

TEST(GyroBiasCovariance, ObservationsOfDifferentRunsAreIndependent) {
  const std::vector<ImuObservation> obs = {Observation({{0, 299}}, 0), Observation({{0, 299}}, 1)};
  const Eigen::MatrixXd k = GyroBiasCovariance_dps2(obs, kFloor_dps, kFrame_s);
  EXPECT_GT(k(0, 0), 0.0);
  EXPECT_DOUBLE_EQ(k(0, 0), k(1, 1));
  EXPECT_EQ(k(0, 1), 0.0);
  EXPECT_EQ(GyroBiasCovariance_dps2(obs, 0.0, kFrame_s).norm(), 0.0);
}

}  // namespace
}  // namespace adahrs::calib
