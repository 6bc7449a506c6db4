// What an IMU calibration strategy returns for one unit: the firmware constants
// (firmware_model/calibration_constants.h), the 1-sigma standard error of each (a struct of the
// same shape, NaN where a number is not estimated) and free-form diagnostics (residual RMS per
// channel, points used, chosen orders, hysteresis, what the firmware cannot hold), which go into
// constants.json (constants_file.h).
#pragma once

#include <nlohmann/json.hpp>

#include "firmware_model/calibration_constants.h"

namespace adahrs::calib {

struct ImuFitResult {
  firmware_model::ImuCalibrationConstants constants;
  firmware_model::ImuCalibrationConstants standard_errors;  ///< NaN = not estimated
  nlohmann::json diagnostics = nlohmann::json::object();
};

/// A constants struct with every number NaN and the identity's temp sensors (for standard errors).
firmware_model::ImuCalibrationConstants NotEstimated();

}  // namespace adahrs::calib
