// The joint strategy (docs/calibration-strategies.md): the whole IMU model estimated from all
// steps at once — thermal bands, six positions, every rate, cross-axis — then mapped into the
// firmware's constant structure.
//
// Model, per channel, in the FORWARD direction (raw output from the known stimulus), written so
// that it is linear in its parameters:
//   accelerometer i:  U_i = o_i + a1_i t + a2_i t^2 + a3_i t^3 + m_i . f_B_g
//   gyro g:           U_g = c_g + b1_g t + b2_g t^2 + b3_g t^3 + n_g . w_B_dps + q2_g w_g^2 + q3_g
//   w_g^3
// t the TEMP counts of the channel's sensor (kThermalSensorOfChannel), m_i (duty per g) and n_g
// (counts per deg/s) 3-vectors that hold scale, misalignment and cross-axis together, w_g the
// rate about the gyro's own axis (the span nonlinearity). Every observation (imu_observations.h)
// is a mean, and because the model is linear in its parameters the mean of its design row (mean
// t, t^2, t^3) is exact. Being linear, the least-squares problem is solved in one step (a
// Levenberg-Marquardt iteration would converge in its first step to the same point), per
// channel, with inverse-variance weights:
//   var = s^2 / n                (s the observation's sample deviation; never below a quarter of
//                                 the datasheet variance, since a smaller measured spread comes
//                                 from too few or quantised samples)
// and thermal bands weighted alike (n replaced by the median band count: every band weighs the
// same). The gyros' bias wander (bias instability, correlated over minutes to hours) does not
// average down in a mean and is shared by observations close in time: the gyro channels are
// solved by generalised least squares with Sigma = diag(var) + K, K the bias process's
// covariance between the observation means (gyro_bias_covariance.h, datasheet floor), by
// whitening with the Cholesky factor of Sigma. A first fit estimates the model-error variance
// (thermal band residuals beyond their noise: drift the polynomial cannot follow); it is added to
// every observation's variance and the fit repeated, so the misfit spreads over the range instead
// of being pinned where the acquisitions are (25 degC).
// Thermal order per channel: 0...3, chosen by 5-fold held-out error over the thermal bands (order
// "auto"; the gyro bias wander enters only as each observation's extra variance there), or
// fixed; the firmware holds at most order 3 (ThermalFit::k[4]).
// Mapping to the firmware constants (calibration_constants.h):
//   thermal xi(t) = alpha1 tau + alpha2 tau^2 + alpha3 tau^3 re-expanded in raw t (k0 follows: xi =
//   0 at the centre 32768 counts, keeping the exporter's thermal block small); O_i = o_i; S_i =
//   m_i[axis_i] (the channel's nominal axis, signed); pair rows P_axis = (m_i/S_i + m_j/S_j)/2, CA
//   = 9.80665 P^-1 (A = CA Ca = 9.80665 f_B_g); gyro thermal likewise; null = c_g; l = the cubic
//   that inverts d = n_gg w + q2 w^2 + q3 w^3 over +-150 deg/s (least squares on 61 rates, l0 = 0);
//   rows N_g = n_g / n_gg, CG = N^-1.
// Uncertainty: Cov(theta) per channel from the weighted fit (residual variance, so model error
// shows); the Cramer-Rao bound of the design from the same design with the DATASHEET noise
// (ImuDatasheetNoise): CRB = (A' Sigma^-1 A)^-1, Sigma = diag(var_datasheet), plus K for the
// gyros (for Gaussian noise and a linear model the Fisher information is exactly A' Sigma^-1 A).
// Both are carried to the 81 firmware numbers by the mapping's Jacobian (central differences):
// Cov_fw = J Cov J'. l0 is fixed at zero by the mapping (the null holds the offset) and reported as
// not estimated. Format 3 (options.format3, the firmware's scale-temperature stages) adds, linear
// in its parameters: sum_p s_p tau^p times the channel's own stimulus (f_axis or w_g; p = 1..P, P
// chosen by leave-one-temperature-out error over the acquisitions, 0 when they were taken at one
// temperature), k2 f_axis^2 (accelerometers), G . f_B_g (gyro g-sensitivity). Mapped to
// F_c(t) = 1 / (1 + delta_c(tau) / S_c) (a least-squares cubic in t over the span),
// q_axis = -(k2_i / S_i + k2_j / S_j) / 2, GS = -CG diag(1 / n_gg) G / g0. The tempco scales
// the channel's own axis only, so cross-axis terms times the tempco (1e-2 x 1e-2) are left out.
// Format 3 also gives each accelerometer two nuisance terms for its die lagging the gyro die
// whose TEMP it is fitted on: tau_dot and tau_dot tau (xi(tau - L tau_dot) ~ xi - L tau_dot xi',
// xi' linear in tau; tau_dot the observation's pooled dt/dtime, ImuObservation::
// t_rate_cnt_per_s), so the logged ramps do not bend the thermal polynomial; the firmware holds
// no lag term (the unit runs at the die temperature it is at).
// Without format 3 the accelerometer scale vs temperature is estimated and reported only.
// Not modelled: supply; die lag without format 3.
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
