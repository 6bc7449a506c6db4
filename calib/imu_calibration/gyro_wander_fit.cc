#include "calib/imu_calibration/gyro_wander_fit.h"

#include <cmath>
#include <limits>

#include "calib/imu_calibration/gyro_bias_covariance.h"

namespace adahrs::calib {
namespace {

constexpr int kFloorSteps = 25;       // over a factor of 100, uniform in log B
constexpr double kFloorRange = 10.0;  // B0 / 10 ... 10 B0
constexpr int kWhiteSteps = 13;       // the white variances' scale s = 2^(w/2 - 2): 1/4 ... 16
constexpr int kWhitePrior = 4;        // s = 1 exactly
constexpr int kFloorPrior = (kFloorSteps - 1) / 2;  // B = B0 exactly
constexpr double kDphPerDps = 3600.0;

// One time scale's covariance K0 (at B0) whitened by the white variances D and diagonalised,
// D^-1/2 K0 D^-1/2 = Q diag(lambda) Q', with the design and data rotated alike: then for
// V = D^1/2 Q (s I + f^2 diag(lambda)) Q' D^1/2 every restricted likelihood costs O(n p^2).
struct Rotated {
  Eigen::VectorXd lambda;
  Eigen::MatrixXd x;
  Eigen::VectorXd y;
  double log_det_d = 0.0;
};

Rotated Rotate(const Eigen::MatrixXd& k0,
               const Eigen::MatrixXd& design,
               const Eigen::VectorXd& y,
               const Eigen::VectorXd& white) {
  const Eigen::VectorXd inv_sqrt = white.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd w = inv_sqrt.asDiagonal() * k0 * inv_sqrt.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(w);
  Rotated r;
  r.lambda = eig.eigenvalues().cwiseMax(0.0);
  r.x = eig.eigenvectors().transpose() * (inv_sqrt.asDiagonal() * design);
  r.y = eig.eigenvectors().transpose() * inv_sqrt.cwiseProduct(y);
  r.log_det_d = white.array().log().sum();
  return r;
}

// The restricted log-likelihood (header) at white scale s and floor factor f.
double RestrictedLogLikelihood(const Rotated& r, double s, double f) {
  const Eigen::VectorXd inv = (s + f * f * r.lambda.array()).inverse().matrix();
  const Eigen::MatrixXd normal = r.x.transpose() * inv.asDiagonal() * r.x;
  const Eigen::LLT<Eigen::MatrixXd> llt(normal);
  if (llt.info() != Eigen::Success) return -std::numeric_limits<double>::infinity();
  const Eigen::VectorXd beta = llt.solve(r.x.transpose() * inv.cwiseProduct(r.y));
  const Eigen::VectorXd e = r.y - r.x * beta;
  const double log_det_v = r.log_det_d - inv.array().log().sum();
  const double log_det_n = 2.0 * llt.matrixLLT().diagonal().array().log().sum();
  return -0.5 * (log_det_v + log_det_n + e.dot(inv.cwiseProduct(e)));
}

}  // namespace

GyroWanderEstimate EstimateGyroWander(const std::vector<ImuObservation>& obs,
                                      const Eigen::MatrixXd& design,
                                      const Eigen::VectorXd& y,
                                      const Eigen::VectorXd& white_cnt2,
                                      double prior_floor_dph,
                                      double cnt_per_dps,
                                      double frame_period_s) {
  const double cnt2_per_dps2 = cnt_per_dps * cnt_per_dps;
  GyroWanderEstimate best;
  double best_ll = -std::numeric_limits<double>::infinity(), prior_ll = best_ll;
  int best_b = 0, best_w = 0;
  size_t best_c = 0;
  for (size_t c = 0; c < kWanderTimeScales.size(); ++c) {
    // K is quadratic in B: computed once per time scale at B0, scaled for each floor.
    const Eigen::MatrixXd k0 =
        GyroBiasCovariance_dps2(
            obs, prior_floor_dph / kDphPerDps, frame_period_s, kWanderTimeScales[c]) *
        cnt2_per_dps2;
    const Rotated rotated = Rotate(k0, design, y, white_cnt2);
    for (int w = 0; w < kWhiteSteps; ++w) {
      const double s = std::exp2(0.5 * w - 2.0);
      for (int b = 0; b < kFloorSteps; ++b) {
        const double factor = std::pow(kFloorRange, 2.0 * b / (kFloorSteps - 1) - 1.0);
        const double ll = RestrictedLogLikelihood(rotated, s, factor);
        if (kWanderTimeScales[c] == 1.0 && b == kFloorPrior && w == kWhitePrior) prior_ll = ll;
        if (ll > best_ll) {
          best_ll = ll;
          best_b = b;
          best_c = c;
          best_w = w;
          best.floor_dph = prior_floor_dph * factor;
          best.time_scale = kWanderTimeScales[c];
          best.white_scale = s;
          best.covariance_cnt2 = factor * factor * k0;
        }
      }
    }
  }
  // The white part's excess (or deficit) rides on the diagonal: the fit adds D to it.
  best.covariance_cnt2.diagonal() += (best.white_scale - 1.0) * white_cnt2;
  best.log_likelihood_gain = best_ll - prior_ll;
  best.at_grid_edge = best_b == 0 || best_b == kFloorSteps - 1 || best_c == 0 ||
                      best_c + 1 == kWanderTimeScales.size() || best_w == 0 ||
                      best_w == kWhiteSteps - 1;
  return best;
}

}  // namespace adahrs::calib
