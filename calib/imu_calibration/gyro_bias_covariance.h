// Covariance, between the means of calibration observations (imu_observations.h), of a gyro's
// slowly wandering bias, from the datasheet's Allan floor B: flicker noise written as the sum of
// four Gauss-Markov processes with correlation times c x (5, 50, 500, 5000 s) and equal variance
// q^2, q set so that their Allan deviation averaged over 10...5000 s (log tau) is B. With the
// datasheet's B and c = 1 this is the calibration's prior (IEEE Std 952 Annex C formulas); the
// joint fit estimates B and c from the recording (gyro_wander_fit.h), so a unit whose wander is
// slower, faster or larger than the datasheet's is fitted with its own.
//
// For one process of variance q^2 and correlation time T the covariance of the means over the
// windows [a1, b1] and [a2, b2] (lengths L1, L2) is
//   q^2 / (L1 L2) * [H(b1 - a2) - H(a1 - a2) - H(b1 - b2) + H(a1 - b2)],
//   H(x) = T^2 (|x| / T + expm1(-|x| / T))       (H'' = exp(-|x| / T), H(0) = H'(0) = 0),
// exact for overlapping, nested and disjoint windows; a window's rows are taken as spread evenly
// over it, and a row stands for one frame period (a window of one row has length T_frame). An
// observation of several windows (a thermal band revisited) is the row-weighted mixture of its
// windows. Observations of different runs are taken as independent (power cycles, hours apart):
// this understates the covariance of the slowest process when runs follow each other closely.
// Units: deg/s squared.
// Left out: rate random walk (off in the datasheet noise model), bias-temperature coupling (the
// thermal polynomial's job), white rate noise (each observation's own variance, added by the fit).
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
