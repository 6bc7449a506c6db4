// Constructed-truth tests of the cross-axis matrices (Eq. 24-29, in the column form derived in
// cross_axis_fit.h).
#include "calib/solvers/cross_axis_fit.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/solvers/linear_least_squares.h"
#include "common/random.h"

namespace adahrs::calib {
namespace {

using ::testing::HasSubstr;

// The sensor-calibrated outputs read m = M f: a non-symmetric M (rotation part 0.015 rad about
// z, plus a symmetric skew and scale errors).
Eigen::Matrix3d Mixing() {
  Eigen::Matrix3d m;
  m << 1.004, -0.015 + 0.003, 0.008, 0.015 + 0.003, 0.997, -0.011, -0.008, 0.011, 1.002;
  return m;
}

std::vector<AxisStepMean> Steps(const Eigen::Matrix3d& m, double reference, double se) {
  std::vector<AxisStepMean> steps;
  for (int axis = 0; axis < 3; ++axis) {
    steps.push_back({10 * (axis + 1) + 1, m.col(axis) * reference, Eigen::Vector3d::Constant(se)});
  }
  return steps;
}

TEST(CrossAxisFit, CorrectsEveryOrientationToTheReference) {
  const Eigen::Matrix3d m = Mixing();
  const double g_local_g = 9.7949 / 9.80665;
  const CrossAxisEstimate e =
      FitCrossAxis("accelerometer cross-axis", Steps(m, g_local_g, 1e-5), 9.7949);
  // C M (g_l e_k) = g_local_mps2 e_k: C = (9.80665) M^-1 to rounding.
  const Eigen::Matrix3d expected = 9.80665 * m.inverse();
  EXPECT_LT((e.matrix - expected).cwiseAbs().maxCoeff(), 1e-12);
  // Off-diagonals of order 0.01 g-to-g, i.e. ~0.1 m/s^2 per g: the mixing's antisymmetric part.
  EXPECT_NEAR(e.matrix(0, 1) / 9.80665, 0.012, 1e-3);
  // Propagated standard error, leading order with K ~ g_l I: se(C_rc) ~ ref * se / g_l^2.
  EXPECT_NEAR(e.standard_error(0, 0), 9.7949 * 1e-5 / (g_local_g * g_local_g), 1e-6);
}

// The thesis's printed form I^-1 diag(g) (I with orientations as rows) applies the transpose:
// for this M it leaves cross-axis errors of ~2 x 0.015 of the reference (30 mg), the size of the
// reference's accelerometer acceptance errors; the column form leaves none.
TEST(CrossAxisFit, PrintedRowFormLeavesTwiceTheRotationPart) {
  const Eigen::Matrix3d m = Mixing();
  const CrossAxisEstimate e = FitCrossAxis("gyro cross-axis", Steps(m, 150.0, 0.01), 150.0);
  const Eigen::Matrix3d i_rows = (m * 150.0).transpose();
  const Eigen::Matrix3d printed = i_rows.inverse() * 150.0;
  const Eigen::Vector3d out_column = e.matrix * (m * Eigen::Vector3d::UnitX() * 150.0);
  const Eigen::Vector3d out_printed = printed * (m * Eigen::Vector3d::UnitX() * 150.0);
  EXPECT_LT((out_column - 150.0 * Eigen::Vector3d::UnitX()).norm(), 1e-9);
  EXPECT_NEAR(out_printed.y() / 150.0, 2 * 0.015, 3e-3);
}

TEST(CrossAxisFit, RefusesMissingOrRepeatedOrientation) {
  auto steps = Steps(Mixing(), 150.0, 0.01);
  steps[2].orientation = 21;
  EXPECT_THAT([&] { FitCrossAxis("gyro cross-axis", steps, 150.0); },
              ::testing::ThrowsMessage<DegenerateDesignError>(
                  HasSubstr("gyro cross-axis: design refused: orientation 21 appears 2 times")));
}

TEST(CrossAxisFit, RefusesWrongFaceAndCollapsedAxes) {
  auto steps = Steps(Mixing(), 150.0, 0.01);
  steps[1].mean = -steps[1].mean;  // orientation 22 data labelled 21
  EXPECT_THAT([&] { FitCrossAxis("gyro cross-axis", steps, 150.0); },
              ::testing::ThrowsMessage<DegenerateDesignError>(
                  HasSubstr("in orientation 21 the up axis reads -149")));
  steps = Steps(Mixing(), 150.0, 0.01);
  steps[2].mean = steps[0].mean + Eigen::Vector3d(0, 0, 2.0);  // 31 step nearly along x
  EXPECT_THAT([&] { FitCrossAxis("gyro cross-axis", steps, 150.0); },
              ::testing::ThrowsMessage<DegenerateDesignError>(HasSubstr("do not span three axes")));
}

}  // namespace
}  // namespace adahrs::calib
