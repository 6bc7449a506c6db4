// The normalised-to-raw change of basis is exact: a surface evaluated through its normalised and
// its raw coefficients agrees at raw ADC-scale inputs, and the raw covariance gives the same
// standard error of a prediction as the normalised one.
#include "calib/solvers/polynomial_basis.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/random.h"

namespace adahrs::calib {
namespace {

TEST(PolynomialBasis, TermNamesFollowTheReferenceLetterOrder) {
  const auto names = PolynomialBasis::ReferenceCubicSurface("x", "y").TermNames();
  const std::vector<std::string> expected = {
      "1", "x", "y", "x^2", "y^2", "x y", "x^3", "y^3", "x y^2", "x^2 y"};
  EXPECT_EQ(names, expected);
}

TEST(PolynomialBasis, RawExpansionMatchesNormalisedEvaluation) {
  common::Rng rng(21);
  const PolynomialBasis basis = PolynomialBasis::ReferenceCubicSurface("x", "y");
  // Code box of a static bridge: x 2.0e6..6.5e6, y 3.1e6..3.6e6 (ADS1254 codes).
  const InputScaling sx = InputScaling::FromRange(2.0e6, 6.5e6);
  const InputScaling sy = InputScaling::FromRange(3.1e6, 3.6e6);
  Eigen::VectorXd a(10);
  for (int i = 0; i < 10; ++i) a[i] = 1e4 * rng.Normal();
  const Eigen::MatrixXd t = basis.NormalisedToRaw(sx, sy);
  const Eigen::VectorXd b = t * a;
  Eigen::MatrixXd cov_a = Eigen::MatrixXd::Identity(10, 10) * 4.0;
  const Eigen::MatrixXd cov_b = t * cov_a * t.transpose();
  for (int k = 0; k < 200; ++k) {
    const double x = rng.Uniform(2.0e6, 6.5e6);
    const double y = rng.Uniform(3.1e6, 3.6e6);
    const Eigen::RowVectorXd row_n = basis.Row(sx.Normalise(x), sy.Normalise(y));
    const Eigen::RowVectorXd row_r = basis.Row(x, y);
    const double z_n = row_n.dot(a);
    // Raw evaluation sums terms up to ~|b_j| |x^i y^j|; double rounding of that sum is the
    // tolerance (relative 1e-16 per term, 1e-13 with margin for the binomial re-expansion).
    const double scale = (row_r.cwiseAbs().transpose().cwiseProduct(b.cwiseAbs())).sum();
    EXPECT_NEAR(row_r.dot(b), z_n, 1e-13 * scale);
    const double var_n = row_n * cov_a * row_n.transpose();
    const double var_r = row_r * cov_b * row_r.transpose();
    // Same rounding argument for the quadratic form: bound by 1e-13 of sum |r_i C_ij r_j|.
    const double var_scale =
        (row_r.cwiseAbs() * cov_b.cwiseAbs() * row_r.cwiseAbs().transpose())(0, 0);
    EXPECT_NEAR(var_r, var_n, 1e-13 * var_scale);
    EXPECT_LT(1e-13 * var_scale, 1e-3 * var_n);  // the check above is meaningful
  }
}

TEST(PolynomialBasis, UnivariateRawExpansionIsExactOnIntegers) {
  // (t - 3) / 2 squared = (t^2 - 6 t + 9) / 4: coefficients 9/4, -6/4, 1/4 exactly.
  const PolynomialBasis basis = PolynomialBasis::Univariate(2, "t");
  const Eigen::MatrixXd t = basis.NormalisedToRaw(InputScaling{3.0, 2.0});
  EXPECT_DOUBLE_EQ(t(0, 2), 2.25);
  EXPECT_DOUBLE_EQ(t(1, 2), -1.5);
  EXPECT_DOUBLE_EQ(t(2, 2), 0.25);
  EXPECT_DOUBLE_EQ(t(0, 1), -1.5);
  EXPECT_DOUBLE_EQ(t(1, 1), 0.5);
}

}  // namespace
}  // namespace adahrs::calib
