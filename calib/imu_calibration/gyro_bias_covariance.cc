#include "calib/imu_calibration/gyro_bias_covariance.h"

#include <cmath>

#include "sensor_sim/gyro_bias_process.h"

namespace adahrs::calib {
namespace {

// H(x) / T^2 for one correlation time (header comment).
double H(double x_s, double t_s) {
  const double u = std::abs(x_s) / t_s;
  return t_s * t_s * (u + std::expm1(-u));
}

// Covariance of the means over two windows of a unit-variance process with correlation time t_s.
double WindowMeanCovariance(double a1, double b1, double a2, double b2, double t_s) {
  const double l1 = b1 - a1, l2 = b2 - a2;
  return (H(b1 - a2, t_s) - H(a1 - a2, t_s) - H(b1 - b2, t_s) + H(a1 - b2, t_s)) / (l1 * l2);
}

}  // namespace

Eigen::MatrixXd GyroBiasCovariance_dps2(const std::vector<ImuObservation>& obs,
                                        double bias_instability_dps, double frame_period_s) {
  const long n = static_cast<long>(obs.size());
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  if (bias_instability_dps <= 0.0) return k;
  const double q = sensor_sim::GyroBiasProcess::PoleSigmaForFloor(bias_instability_dps);
  for (long i = 0; i < n; ++i) {
    for (long j = i; j < n; ++j) {
      if (obs[i].run != obs[j].run) continue;
      double sum = 0.0;
      for (const TimeWindow& w1 : obs[i].windows) {
        for (const TimeWindow& w2 : obs[j].windows) {
          const double weight = (static_cast<double>(w1.rows) / obs[i].count) * (static_cast<double>(w2.rows) / obs[j].count);
          for (double t_s : sensor_sim::GyroBiasProcess::kCorrelationTimes_s) {
            sum += weight * WindowMeanCovariance(w1.first_s, w1.last_s + frame_period_s, w2.first_s,
                                                 w2.last_s + frame_period_s, t_s);
          }
        }
      }
      k(i, j) = k(j, i) = q * q * sum;
    }
  }
  return k;
}

}  // namespace adahrs::calib
