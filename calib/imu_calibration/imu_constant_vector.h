// The IMU's firmware numbers as one vector (the parameter block of the Ceres split, used for
// covariances, standard errors and reports): every number of a constants set
// (calibration_constants.h) in a fixed order, format-3 terms last (zeros for a format-2 set).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "firmware_model/calibration_constants.h"

namespace adahrs::calib {

/// Highest thermal order the firmware holds (firmware_model::kImuThermalDegree).
inline constexpr int kMaxThermalOrder = 3;
/// How many firmware numbers FlattenConstants gives: every number of a constants set, format-3
/// terms last (zeros for a format-2 set): thermal, accelerometer, gyro, CA, CG, then scale factors,
/// q and GS.
inline constexpr int kImuFirmwareNumbers =
    9 * (kMaxThermalOrder + 1) + 6 * 2 + 3 * 5 + 9 + 9 + 9 * 4 + 3 + 9;

/// The numbers of a format-2 set (the first kImuFormat2Numbers of the flattened vector): constants
/// files written before format 3 carry a CRB covariance of this size.
inline constexpr int kImuFormat2Numbers = 9 * (kMaxThermalOrder + 1) + 6 * 2 + 3 * 5 + 9 + 9;

/// The firmware numbers in a fixed order (thermal k 9x4, accel O,S 6x2, gyro null,l0..l3 3x5,
/// CA 3x3, CG 3x3, scale factors 9x4, q 3, GS 3x3) and back; names for reports
/// ("thermal[0].k[1]"). Unflatten keeps `like`'s scale_temperature.active and spans.
Eigen::VectorXd FlattenConstants(const firmware_model::ImuCalibrationConstants& c);
firmware_model::ImuCalibrationConstants UnflattenConstants(
    const Eigen::VectorXd& v, const firmware_model::ImuCalibrationConstants& like);
std::vector<std::string> ConstantNames();

}  // namespace adahrs::calib
