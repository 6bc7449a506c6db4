// Reference cross-axis matrices (thesis section 2.8.4, Eq. 24-29): with the unit in orientations
// 11, 21, 31 (x, y, z up) under a known reference along the up axis (local gravity for CA; +150
// deg/s of the rate table for CG), the means of the sensor-calibrated outputs form K, holding the
// means as COLUMNS, and C = reference * K^-1 (the column form; the thesis's printed I^-1 form
// leaves errors of twice the misalignment's rotation part). Standard errors by first-order
// propagation with the means independent.
// Frames and units: body axes B, orientation codes of frames-and-units.md; Ca in g, Cg in deg/s.
// Derivation and refusals: docs/calibration-solvers.md ("Models", Cross-axis).
// Left out: the reference magnitude's own uncertainty, fixture tilt.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

namespace adahrs::calib {

/// Mean output vector (x, y, z) of one orientation step with its standard errors.
struct AxisStepMean {
  int orientation = 0;  ///< 11, 21 or 31
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d standard_error = Eigen::Vector3d::Zero();
};

struct CrossAxisOptions {
  /// Near-identity K (misalignments ~1 deg, scale errors of a few %) has cond(K) < 1.2; two steps
  /// in the same orientation make it singular.
  double max_condition = 2.0;
};

struct CrossAxisEstimate {
  Eigen::Matrix3d matrix = Eigen::Matrix3d::Identity();  ///< C, output units per input unit
  Eigen::Matrix3d standard_error = Eigen::Matrix3d::Zero();
  double condition_number = 0.0;  ///< of K
};

/// C = reference * K^-1 from steps 11, 21, 31; `context` leads every message
/// ("accelerometer cross-axis"); throws DegenerateDesignError with the reason.
CrossAxisEstimate FitCrossAxis(const std::string& context,
                               const std::vector<AxisStepMean>& steps,
                               double reference,
                               const CrossAxisOptions& options = {});

}  // namespace adahrs::calib
