// Reference gyro scale factor and nonlinearity (thesis section 2.8.3, Eq. 23): the gyro under
// calibration sees the table rates (reference: -150 -100 -50 0 50 100 150 deg/s about its axis);
// the thermally compensated means T_k are normalised by the 0 deg/s mean, d_k = T_k - T_0, and
//   rate_dps = l0 + l1 d + l2 d^2 + l3 d^3
// is fitted to the reference rates (firmware_model::GyroCubicFit with null_cnt = T_0). The fit is
// done in d normalised to [-1, 1] and re-expanded (polynomial_basis.h); reference magnitudes: l1 ~
// 4.7-4.9e-5 deg/s per count, l3 ~ 1e-20 (Table 18). Normalising removes the bias, whatever its
// source (null, Earth rate, g-sensitivity in that orientation).
// Standard errors: from the residual variance (n - 4 degrees of freedom, 3 for the reference's
// seven rates) with equal weights, as the reference fits; se(null_cnt) is the 0 deg/s mean's.
// The 0 deg/s step is the one whose mean reported rate is within kNullStepTolerance_dps of 0.
// Refused: no 0 deg/s step, fewer than min_rates distinct rates (too few rates), a degenerate
// design. Not modelled: scale factor vs temperature (the reference's future work), the rate table's
// own rate error, noise in d (the regressor; its relative size ~1e-6 makes the bias negligible).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "calib/solvers/linear_least_squares.h"
#include "firmware_model/calibration_constants.h"

namespace adahrs::calib {

/// A step whose mean reported rate is this close to 0 is the null step (the ATL resolves 1e-4
/// deg/s; its rate loop settles the last of a deceleration within the first second).
inline constexpr double kNullStepTolerance_dps = 0.01;

/// Mean thermally compensated output of the gyro under calibration at one table rate.
struct GyroRateMean {
  double rate_dps = 0.0;  ///< reference (table) rate about the gyro's axis
  double t_cnt = 0.0;     ///< mean T, counts
  double t_cnt_se = 0.0;  ///< its standard error, counts
};

struct GyroScaleOptions {
  int min_rates = 5;  ///< distinct rates: 4 coefficients plus one residual degree of freedom
  LeastSquaresOptions least_squares;
};

struct GyroScaleEstimate {
  firmware_model::GyroCubicFit fit;  ///< null_cnt, l (deg/s per count^i)
  double null_se_cnt = 0.0;
  std::array<double, 4> l_se{};
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();  ///< of l
  double residual_rms_dps = 0.0;
  int rates = 0;
  double condition_number = 0.0;
};

/// Fits gyro `gyro` (named in messages); throws DegenerateDesignError with the reason.
GyroScaleEstimate FitGyroScale(const std::string& gyro,
                               const std::vector<GyroRateMean>& steps,
                               const GyroScaleOptions& options = {});

}  // namespace adahrs::calib
