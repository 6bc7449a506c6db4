// Reference thermal model (thesis section 2.8.1, Eq. 4-11): per channel (six accelerometer duty
// channels, three gyro count channels) the drift xi(t) = k0 + k1 t + k2 t^2 of the raw output U
// against temperature counts t over a thermal profile, applied as T = U - xi(t). Samples are
// grouped in temperature bands of band_width_cnt, every band weighing the same (sandwich
// covariance), streamed into per-band normal equations in normalised temperature. Reported: the
// fit over all samples (the constants) and up- and down-ramp fits with their largest gap
// (thermal hysteresis).
// Units: U in duty (T1/T2 - 0.5) or counts; t in counts of the driving sensor.
// Derivation, weighting and refusals: docs/calibration-solvers.md ("Models", "The driver").
// Left out: the die's lag itself (the reference has none), orders other than 2, correlation of
// successive samples (standard errors are then optimistic; the residual rms shows the model
// error).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "calib/solvers/linear_least_squares.h"

namespace adahrs::calib {

enum class ThermalSegment { kUpRamp, kDownRamp, kSoak };

struct ThermalSample {
  double temp_cnt = 0.0;  ///< temperature counts of the driving sensor
  double value = 0.0;     ///< raw channel output U (duty, or gyro counts)
  ThermalSegment segment = ThermalSegment::kSoak;
};

struct ThermalFitOptions {
  /// Width of a temperature band, counts. 110 counts ~ 1 degC: 16 summed 12-bit conversions of
  /// the ADXRS150 TEMP pin, 16 * 4096 / 5 V * 8.4 mV/K (physics.md section 2, R).
  double band_width_cnt = 110.0;
  int min_bands = 4;
  LeastSquaresOptions least_squares;
};

/// One quadratic in raw temperature counts with its uncertainty.
struct ThermalPolynomial {
  std::array<double, 3> k{};     ///< xi = k0 + k1 t + k2 t^2, U units per count^i
  std::array<double, 3> k_se{};  ///< standard errors of k
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double temp_min_cnt = 0.0;  ///< the fitted temperature range
  double temp_max_cnt = 0.0;
  int bands = 0;
  int samples = 0;
  double residual_rms = 0.0;  ///< U units
  double condition_number = 0.0;

  double Drift(double temp_cnt) const {
    return k[0] + k[1] * temp_cnt + k[2] * temp_cnt * temp_cnt;
  }
  /// Standard error of Drift(temp_cnt) from the covariance.
  double DriftStandardError(double temp_cnt) const;
};

struct ThermalDriftResult {
  ThermalPolynomial all;                  ///< every sample: the constants
  std::optional<ThermalPolynomial> up;    ///< up-ramp samples only
  std::optional<ThermalPolynomial> down;  ///< down-ramp samples only
  std::string ramp_note;                  ///< why up or down is absent (empty when both exist)
  /// max |xi_up - xi_down| over the common range, U units (0 when a direction is absent)
  double hysteresis = 0.0;
  double hysteresis_at_temp_cnt = 0.0;
};

/// Fits channel `channel` (its name leads every message); throws DegenerateDesignError.
ThermalDriftResult FitThermalDrift(const std::string& channel,
                                   const std::vector<ThermalSample>& samples,
                                   const ThermalFitOptions& options = {});

}  // namespace adahrs::calib
