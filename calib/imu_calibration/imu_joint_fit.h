// The joint strategy: the whole IMU model estimated from all steps at once (thermal bands, six
// positions, every rate, cross-axis) in the forward direction, linear in its parameters, per
// channel: accelerometer U_i = o_i + thermal cubic + m_i . f_B_g (+ format-3 scale tempco, k2
// f_axis^2, die-lag terms); gyro U_g = c_g + thermal cubic + n_g . w_B_dps + q2 w_g^2 + q3 w_g^3
// (+ format-3 tempco and g-sensitivity). Weighted least squares with s^2/n variances and a
// model-error term; gyros by generalised least squares against the bias-wander covariance
// (gyro_bias_covariance.h). Thermal order 0...3 per channel by held-out error. Then mapped to the
// firmware constants (calibration_constants.h) with standard errors and the design's Cramer-Rao
// bound carried to the 81 firmware numbers by the mapping's Jacobian.
// Frames and units: body axes B; f_B in g, w_B in deg/s; raw outputs in duty or counts; t the TEMP
// counts of the channel's sensor (kThermalSensorOfChannel), tau = (t - 32768) / 4096.
// Derivations: docs/calibration-strategies.md ("`joint`: the improved strategy", "Format 3 on the
// truth profile").
// Left out: supply; cross-axis terms times the tempco; without format 3, die lag (and the
// accelerometer scale tempco is then estimated and reported only, not held).
#pragma once

#include <optional>

#include "calib/imu_calibration/imu_constant_vector.h"
#include "calib/imu_calibration/imu_fit_result.h"
#include "calib/imu_calibration/imu_observations.h"

namespace adahrs::calib {

/// Datasheet noise of the sensors (ADXL210E, ADXRS150 typical; docs/models/), for the CRB.
struct ImuDatasheetNoise {
  double accel_density_ug_per_rthz = 200.0;  ///< ADXL210E typical
  double accel_filter_tau_s = 3.2e-3;        ///< 32 kOhm x 0.1 uF
  double accel_sensitivity_duty_per_g = 0.04;
  double gyro_density_dps_per_rthz = 0.05;  ///< ADXRS150 typical
  double gyro_bias_floor_dph = 75.0;        ///< Allan floor (E)
  double gyro_cnt_per_dps = 20971.52;       ///< 16 * 2^19 / 5 V * 12.5 mV/(deg/s)
  double frame_period_s = 0.01;
};

struct ImuJointOptions {
  std::optional<int> thermal_order;  ///< 0..kMaxThermalOrder; empty = chosen by held-out error
  int folds = 5;
  /// Equal weights instead of inverse variances (noise-free data, e.g. projecting a true unit).
  bool unit_weights = false;
  /// Each gyro's bias wander (Allan floor, time scale, white scale) estimated from the recording
  /// (gyro_wander_fit.h) instead of the datasheet's prior (noise.gyro_bias_floor_dph, time scale
  /// 1). Off by default: measured on 20 units it did not make the bound more honest
  /// (docs/calibration-strategies.md "Model-form mismatch").
  bool estimate_gyro_wander = false;
  /// Fit the firmware's format-3 terms too (calibration_constants.h ImuScaleTemperature): scale
  /// factors as polynomials in temperature (order by held-out error over the acquisitions'
  /// temperatures), the accelerometers' f_axis^2 and the gyros' g-sensitivity.
  bool format3 = false;
  /// Format 3: the scale factors' order in temperature, 0..3; empty = chosen by held-out error.
  std::optional<int> scale_order;
  /// Format 3: each accelerometer's die-lag nuisance terms (tau_dot, tau_dot tau). Off for
  /// steady-state observations (a noise-free grid, e.g. projecting a true unit): their TEMP slope
  /// is zero, and its rounding residue is no regressor.
  bool die_lag_terms = true;
  ImuDatasheetNoise noise;
};

/// Fits the joint model to `observations` (named `serial` in messages); diagnostics hold the
/// chosen orders, residuals, the CRB covariance ("crb_covariance", kImuFirmwareNumbers square)
/// and, for a format-2 fit, the scale-vs-temperature estimate the firmware would not hold. Throws
/// DegenerateDesignError with the reason.
ImuFitResult FitImuJoint(const std::string& serial,
                         const std::vector<ImuObservation>& observations,
                         const ImuJointOptions& options = {});

}  // namespace adahrs::calib
