// Covariance, between the means of calibration observations (imu_observations.h), of a gyro's
// slowly wandering bias: the datasheet's Allan floor B as four Gauss-Markov processes with
// correlation times c x (5, 50, 500, 5000 s), in closed form for window means (IEEE Std 952
// Annex C). With the datasheet's B and c = 1 this is the calibration's prior; gyro_wander_fit.h
// estimates B and c from the recording. Runs are taken as independent of each other.
// Units: (deg/s)^2; times in s.
// Derivation (the window-mean formula, row spreading, revisited bands):
// docs/calibration-strategies.md ("`joint`: the improved strategy", the bias-wander covariance).
// Left out: rate random walk, bias-temperature coupling (the thermal polynomial's job), white rate
// noise (each observation's own variance, added by the fit).
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "calib/imu_calibration/imu_observations.h"

namespace adahrs::calib {

/// n x n covariance, (deg/s)^2, of the bias-instability process between the means of `obs`, for
/// the Allan floor `bias_instability_dps`, frame period `frame_period_s` and the poles'
/// correlation times scaled by `time_scale`.
Eigen::MatrixXd GyroBiasCovariance_dps2(const std::vector<ImuObservation>& obs,
                                        double bias_instability_dps,
                                        double frame_period_s,
                                        double time_scale = 1.0);

}  // namespace adahrs::calib
