// Reference cross-axis matrices (thesis section 2.8.4, Eq. 24-29): with the unit in orientations
// 11, 21, 31 (x, y, z up) under a known reference along the up axis (local gravity for the
// accelerometers, CA; +150 deg/s of the rate table for the gyros, CG), the means of the sensor-
// calibrated outputs (Ca per axis in g, or Cg in deg/s) form a 3x3 matrix, and the correction C
// makes C * mean_k = reference * e_k for each orientation k.
// Frame algebra: let K hold the means as COLUMNS, K = [m_11 m_21 m_31] (the thesis's I, J hold
// them as rows, I = K'). Applied as A = C * Ca on column vectors (Eq. 26, 29) the requirement
// C K = reference * 1 gives C = reference * K^-1 = reference * (I')^-1. The thesis prints
// I^-1 * diag(9.81), which equals this only when K is symmetric; for a misalignment with an
// antisymmetric (rotation) part it leaves cross-axis errors of twice that part (~2 x 0.015 g
// = 30 mg at the reference's off-diagonals, the size of its accelerometer acceptance errors).
// Standard errors by first-order propagation, d(K^-1) = -K^-1 dK K^-1, with the means
// independent:  var(C_rc) = reference^2 sum_ij (K^-1_ri K^-1_jc)^2 se(K_ij)^2.
// Refused: a missing or repeated orientation among 11, 21, 31, a non-positive diagonal (the axis
// was not up), or cond(K) above max_condition (the orientations do not span three axes).
// Not modelled: the reference magnitude's own uncertainty, fixture tilt.
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
