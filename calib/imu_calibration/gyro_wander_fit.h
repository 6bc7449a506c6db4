// A gyro's bias wander estimated from the recording: the Allan floor B and the time scale c of
// the flicker model of gyro_bias_covariance.h, chosen by restricted maximum likelihood (REML:
// H. D. Patterson and R. Thompson, Biometrika 58, 1971) over the channel's linear model
// y = X beta + e, e ~ N(0, s D + K(B, c)), D the observations' own (white) variances from the
// datasheet noise and s a free scale of them (what the noise model misses of the white part
// would otherwise be taken for fast wander):
//   l(B, c) = -1/2 [ log|V| + log|X' V^-1 X| + y' (V^-1 - V^-1 X (X' V^-1 X)^-1 X' V^-1) y ],
// which does not depend on beta and does not shrink the variance by the fitted terms. The
// search: B from a tenth to ten times the datasheet floor (25 steps, uniform in log B), s from
// 1/4 to 16 (13 steps) and c in kWanderTimeScales; the datasheet's (B0, 1, 1) is on the grid, so
// the estimate never fits the data worse than the prior. One eigendecomposition of D^-1/2 K D^-1/2
// per time scale makes each (B, s) cost O(n p^2). Units: B in deg/h, the covariance in counts^2
// (counts per deg/s given).
// Left out: a rate random walk as its own term (the slowest pole stands for it over a run's
// length), a floor that changes with temperature; each gyro is estimated on its own.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Dense>

#include "calib/imu_calibration/imu_observations.h"

namespace adahrs::calib {

inline constexpr std::array<double, 7> kWanderTimeScales = {0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0};

struct GyroWanderEstimate {
  double floor_dph = 0.0;
  double time_scale = 1.0;           ///< c: the poles at c x (5, 50, 500, 5000 s)
  double white_scale = 1.0;          ///< s: the white variances' factor
  double log_likelihood_gain = 0.0;  ///< restricted log-likelihood over the datasheet prior's
  bool at_grid_edge = false;         ///< B or c on the search's boundary
  Eigen::MatrixXd covariance_cnt2;   ///< K(B, c) + (s - 1) D between the observations, counts^2:
                                     ///< what the fit adds to the observations' own variances D
};

/// `design` rows and `y` are the channel's observations in the order of `obs` (all of them),
/// `white_cnt2` their own variances; `prior_floor_dph` the datasheet's B0.
GyroWanderEstimate EstimateGyroWander(const std::vector<ImuObservation>& obs,
                                      const Eigen::MatrixXd& design,
                                      const Eigen::VectorXd& y,
                                      const Eigen::VectorXd& white_cnt2,
                                      double prior_floor_dph,
                                      double cnt_per_dps,
                                      double frame_period_s);

}  // namespace adahrs::calib
