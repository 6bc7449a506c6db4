#include "calib/solvers/cross_axis_fit.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "calib/solvers/linear_least_squares.h"

namespace adahrs::calib {

CrossAxisEstimate FitCrossAxis(const std::string& context,
                               const std::vector<AxisStepMean>& steps,
                               double reference,
                               const CrossAxisOptions& options) {
  Eigen::Matrix3d k = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d k_se = Eigen::Matrix3d::Zero();
  for (int axis = 0; axis < 3; ++axis) {
    const int orientation = 10 * (axis + 1) + 1;
    int found = 0;
    for (const AxisStepMean& s : steps) {
      if (s.orientation != orientation) continue;
      ++found;
      k.col(axis) = s.mean;
      k_se.col(axis) = s.standard_error;
    }
    if (found != 1) {
      throw DegenerateDesignError(
          fmt::format("{}: design refused: orientation {} appears {} times (11, 21 and 31 are "
                      "needed once each)",
                      context,
                      orientation,
                      found));
    }
    if (!(k(axis, axis) > 0.0)) {
      throw DegenerateDesignError(fmt::format(
          "{}: design refused: in orientation {} the up axis reads {:.6g}, not a positive "
          "reference (wrong face or sign)",
          context,
          orientation,
          k(axis, axis)));
    }
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(k);
  const Eigen::Vector3d s = svd.singularValues();
  CrossAxisEstimate out;
  out.condition_number = s[2] > 0.0 ? s[0] / s[2] : std::numeric_limits<double>::infinity();
  if (!(out.condition_number <= options.max_condition)) {
    throw DegenerateDesignError(fmt::format(
        "{}: design refused: the three orientation means do not span three axes (condition number "
        "{:.3g}, limit {:.3g})",
        context,
        out.condition_number,
        options.max_condition));
  }
  const Eigen::Matrix3d k_inv = k.inverse();
  out.matrix = reference * k_inv;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      double var = 0.0;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          const double partial = reference * k_inv(r, i) * k_inv(j, c);
          var += partial * partial * k_se(i, j) * k_se(i, j);
        }
      }
      out.standard_error(r, c) = std::sqrt(var);
    }
  }
  return out;
}

}  // namespace adahrs::calib
