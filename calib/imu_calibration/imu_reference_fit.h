// The reference strategy: sequential, exactly as the reference method runs it (reference-method.md,
// Method 2-5), on the data LoadImuRuns selected: thermal (Eq. 10-11, quadratic per channel),
// six-position offset and scale (Eq. 17-20) on thermally compensated means, gyro cubic (Eq. 23),
// cross-axis (Eq. 25, 28, column form). Each channel's thermometer is kThermalSensorOfChannel
// (accelerometer chip k uses TEMP k, the gyro on its board).
// Frames and units: body axes B, orientation codes of frames-and-units.md; raw duty and counts in,
// firmware constants (calibration_constants.h) out; rates in deg/s, local gravity in m/s^2.
// Steps, pooling and refusals (DegenerateDesignError / ImuInputError):
// docs/calibration-strategies.md ("`reference`: the reference method exactly", "Selecting the
// calibration data") and docs/calibration-solvers.md ("Models").
// Left out: anything the firmware constants cannot hold (scale vs temperature, accelerometer
// nonlinearity, g-sensitivity, lag), see the joint strategy.
#pragma once

#include <array>
#include <optional>

#include "calib/constants/imu_stage.h"
#include "calib/imu_calibration/imu_fit_result.h"
#include "calib/imu_calibration/imu_run_data.h"
#include "calib/solvers/thermal_drift_fit.h"

namespace adahrs::calib {

/// The constants a unit holds from the earlier stages of the staged process, with their standard
/// errors (the previous stage's constants file).
struct ImuStageBase {
  firmware_model::ImuCalibrationConstants constants;
  firmware_model::ImuCalibrationConstants standard_errors;
};

struct ImuReferenceOptions {
  ThermalFitOptions thermal;
  /// The staged process (calib/constants/imu_stage.h): fit this stage alone. The earlier stages
  /// come from `base` (required past the thermal stage), the later stages hold their defaults
  /// (calibration_constants.h; cross-axis the identity). Empty: the four steps at once.
  std::optional<ImuStage> stage;
  std::optional<ImuStageBase> base;
};

/// Sequential reference fit of one unit (or of one stage, options.stage). Throws ImuInputError
/// when a stage past the thermal one has no base.
ImuFitResult FitImuReference(const ImuUnitData& unit,
                             double local_gravity_mps2,
                             const ImuReferenceOptions& options = {});

/// Per-channel means of `samples` through ImuReference(constants, mode): mean and standard error.
struct ChannelMeans {
  std::array<double, 9> mean{};
  std::array<double, 9> standard_error{};
  int count = 0;
};
ChannelMeans MeansOf(const firmware_model::ImuCalibrationConstants& constants,
                     firmware_model::ImuCompensationMode mode,
                     const std::vector<ImuSample>& samples,
                     const std::string& context);

}  // namespace adahrs::calib
