// Reference thermal model (thesis section 2.8.1, Eq. 4-11): per channel (six accelerometer duty
// channels, three gyro count channels) the drift xi(t) = k0 + k1 t + k2 t^2 of the raw output U
// against temperature counts t over a thermal profile, applied as T = U - xi(t).
//
// Inputs: per-packet samples of one channel, in its raw units (accelerometer duty T1/T2 - 0.5,
// gyro counts), with the temperature counts of the sensor that drives its compensation and the
// profile segment (up-ramp, down-ramp, soak) the packet was taken in. The unit is static in one
// orientation throughout, so U - xi carries the orientation's gravity term in k0; the six-position
// offset later absorbs it.
// Weighting: samples are grouped into temperature bands of band_width_cnt; each sample weighs
// 1 / (samples in its band), so every band weighs the same whatever the heating or cooling rate
// (a slow ramp or a soak would otherwise dominate the fit). The noise is taken as equal per sample,
// so the covariance is the sandwich form (linear_least_squares.h, kBalancing) scaled by the
// residual variance.
// Method: the rows are never held as a design matrix. The fit streams them into per-band sums of
// the band-weighted normal equations in the normalised temperature u on [-1, 1] (where the
// equilibrated design of 1, u, u^2 is well conditioned), solves them with the driver's rank and
// condition tests, and takes the residuals in a second pass.
// Reported: the fit over all samples (the constants) and, separately, over up-ramps and over
// down-ramps with the largest difference of the two curves over their common temperature range
// (thermal hysteresis, including any lag of the die behind the thermometer).
// Refused: fewer than min_bands distinct temperature bands (too few temperatures for a quadratic
// with a residual degree of freedom), or a degenerate design. A ramp direction with too few bands
// is reported as absent with the reason, not refused.
// Not modelled: the lag itself (the reference has none), orders other than 2, correlation of
// successive samples (standard errors assume independent samples, so a drifting bias makes them
// optimistic; the residual rms shows the model error).
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
