#include "calib/imu_calibration/gyro_bias_covariance.h"

#include <array>
#include <cmath>

namespace adahrs::calib {
namespace {

// The calibration's own prior for a datasheet Allan floor B (header comment): flicker noise as
// equal-variance first-order Gauss-Markov poles one decade apart, which gives a PSD ~ 1/f between
// the corners and a flat Allan floor over the band where datasheets quote it.
constexpr std::array<double, 4> kPoleCorrelationTimes_s = {5.0, 50.0, 500.0, 5000.0};
constexpr double kFloorBandMin_s = 10.0;
constexpr double kFloorBandMax_s = 5000.0;
constexpr int kFloorBandPoints = 201;

// Allan variance at tau of a unit-variance Gauss-Markov process of correlation time t
// (IEEE Std 952-1997 Annex C): (2 t / tau) [1 - (3 - 4 e^-x + e^-2x) / (2x)], x = tau / t.
double UnitPoleAvar(double tau_s, double t_s) {
  const double x = tau_s / t_s;
  return (2.0 * t_s / tau_s) * (1.0 - (3.0 - 4.0 * std::exp(-x) + std::exp(-2.0 * x)) / (2.0 * x));
}

// The pole standard deviation whose sum's Allan deviation, averaged over log(tau) in the band,
// equals the floor B.
double PoleSigmaForFloor(double floor_dps, double time_scale) {
  double sum = 0.0;
  for (int i = 0; i < kFloorBandPoints; ++i) {
    const double u = static_cast<double>(i) / (kFloorBandPoints - 1);
    const double tau_s =
        std::exp(std::log(kFloorBandMin_s) + u * std::log(kFloorBandMax_s / kFloorBandMin_s));
    double avar = 0.0;
    for (double t_s : kPoleCorrelationTimes_s) avar += UnitPoleAvar(tau_s, time_scale * t_s);
    sum += std::sqrt(avar);
  }
  return floor_dps / (sum / kFloorBandPoints);
}

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
                                        double bias_instability_dps,
                                        double frame_period_s,
                                        double time_scale) {
  const long n = static_cast<long>(obs.size());
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  if (bias_instability_dps <= 0.0) return k;
  const double q = PoleSigmaForFloor(bias_instability_dps, time_scale);
  for (long i = 0; i < n; ++i) {
    for (long j = i; j < n; ++j) {
      if (obs[i].run != obs[j].run) continue;
      double sum = 0.0;
      for (const TimeWindow& w1 : obs[i].windows) {
        for (const TimeWindow& w2 : obs[j].windows) {
          const double weight = (static_cast<double>(w1.rows) / obs[i].count) *
                                (static_cast<double>(w2.rows) / obs[j].count);
          for (double t_s : kPoleCorrelationTimes_s) {
            sum += weight * WindowMeanCovariance(w1.first_s,
                                                 w1.last_s + frame_period_s,
                                                 w2.first_s,
                                                 w2.last_s + frame_period_s,
                                                 time_scale * t_s);
          }
        }
      }
      k(i, j) = k(j, i) = q * q * sum;
    }
  }
  return k;
}

}  // namespace adahrs::calib
