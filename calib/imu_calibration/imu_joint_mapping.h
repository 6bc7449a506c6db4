// The joint IMU fit's channel models mapped to the firmware's numbers (calibration_constants.h,
// docs/calibration-strategies.md): thermal polynomials re-expanded from tau to TEMP counts, the
// accelerometer pairs' offsets and 1/S, the gyro null and inverse cubic, the cross-axis matrices
// CA and CG, and the format-3 scale factors, q and GS; and the covariance of those numbers through
// the mapping's numerical Jacobian. The firmware mapping of the Ceres split.
// Left out: choosing the models' terms (imu_joint_model.h).
#pragma once

#include <array>

#include <Eigen/Dense>

#include "calib/imu_calibration/imu_joint_model.h"

namespace adahrs::calib::joint_fit {

// F_c(t) = 1 / (1 + delta_c(tau) / S_c) as a least-squares cubic in (t - origin) over the
// sensor's span, delta_c = sum_p theta_p tau^p and S_c the channel's own stimulus coefficient.
std::array<double, 4> ScaleFactorCubic(const ChannelModel& m,
                                       const Eigen::VectorXd& theta,
                                       double own_scale,
                                       const fm::TempSensorSpan& span);

// The format-3 terms (calibration_constants.h ImuScaleTemperature): the scale factors, q_axis =
// -(k2_i / S_i + k2_j / S_j) / 2 (the pair mean's f^2 coefficient, removed), and GS = -CG
// diag(1 / n_gg) Gsens / g0 (Gsens in counts per g, A = g0 f).
void MapScaleTemperature(const std::array<ChannelModel, 9>& models,
                         const std::array<Eigen::VectorXd, 9>& theta,
                         const std::array<std::array<double, 2>, 3>& temp_span_cnt,
                         const Eigen::Matrix3d& cg,
                         fm::ImuCalibrationConstants* c);

// The channel models -> the firmware numbers (the mapping of the header comment); each
// channel's thermal span is `temp_span_cnt[sensor]`.
fm::ImuCalibrationConstants Map(const std::array<ChannelModel, 9>& models,
                                const std::array<Eigen::VectorXd, 9>& theta,
                                const std::array<std::array<double, 2>, 3>& temp_span_cnt);

// Cov of the firmware numbers from per-channel covariances through the mapping's Jacobian.
Eigen::MatrixXd Propagate(const std::array<ChannelModel, 9>& models,
                          const std::array<Eigen::VectorXd, 9>& theta,
                          const std::array<Eigen::MatrixXd, 9>& cov,
                          const std::array<std::array<double, 2>, 3>& temp_span_cnt);

}  // namespace adahrs::calib::joint_fit
