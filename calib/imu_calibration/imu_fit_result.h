// What an IMU calibration strategy returns for one unit: the firmware constants
// (firmware_model/calibration_constants.h), the 1-sigma standard error of each (a struct of the
// same shape, NaN where a number is not estimated) and the fit's diagnostics
// (imu_fit_diagnostics.h), which go into constants.json (constants_file.h).
#pragma once

#include "calib/constants/imu_fit_diagnostics.h"
#include "firmware_model/calibration_constants.h"

namespace adahrs::calib {

struct ImuFitResult {
  firmware_model::ImuCalibrationConstants constants;
  firmware_model::ImuCalibrationConstants standard_errors;  ///< NaN = not estimated
  ImuFitDiagnostics diagnostics;
};

/// A constants struct with every number NaN and the identity's temp sensors (for standard errors).
firmware_model::ImuCalibrationConstants NotEstimated();

}  // namespace adahrs::calib
