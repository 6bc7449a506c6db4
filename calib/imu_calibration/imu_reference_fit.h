// The reference strategy (reference-method.md, Method 2-5; docs/calibration-strategies.md):
// sequential, exactly as the reference method runs it, on the data LoadImuRuns selected:
//   1. thermal (Eq. 10-11): per channel xi(t) = k0 + k1 t + k2 t^2 over the thermal_profile rows
//      (thermal_drift_fit.h: every 1 degC band weighs the same; up- and down-ramps fitted and
//      reported separately, their largest gap reported as hysteresis);
//   2. six-position offset and scale (Eq. 17-20) on thermally compensated means; acquisitions of
//      the same orientation (e.g. the thermal run's accel step) are pooled;
//   3. gyro cubic (Eq. 23) per gyro from the acquisitions whose up axis is the gyro's axis, the
//      reference rate being the table's reported rate about that axis;
//   4. cross-axis (Eq. 25, 28, column form): CA from the rest acquisitions in 11/21/31 with the
//      station's local gravity, CG from those at the largest rate (each column scaled to 150 deg/s
//      by its reported rate). The cross_axis step's acquisitions are used when present, else
//      the accel steps' and the gyro steps' at their largest rate.
// Temperature sensor driving each channel (a documented choice, ThermalSensorOfChannel): the
// accelerometers have no thermometer, every die follows the same chamber air, and chip k sits
// on the board of gyro k, so chip k (az1/ax1, ay1/az2, ax2/ay2) uses TEMP k; gyro g uses its own.
// Refused (DegenerateDesignError / ImuInputError with the reason): no thermal rows, a missing
// orientation, fewer than 5 rates or no 0 deg/s acquisition for a gyro, too few temperatures.
// Not modelled: anything the firmware constants cannot hold (scale vs temperature, accelerometer
// nonlinearity, g-sensitivity, lag), see the improved strategies.
#pragma once

#include <array>

#include "calib/imu_calibration/imu_fit_result.h"
#include "calib/imu_calibration/imu_run_data.h"
#include "calib/solvers/thermal_drift_fit.h"

namespace adahrs::calib {

struct ImuReferenceOptions {
  ThermalFitOptions thermal;
};

/// Sequential reference fit of one unit.
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
