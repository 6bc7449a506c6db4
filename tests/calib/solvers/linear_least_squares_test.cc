// Truth tests of the generic least-squares driver: estimates and standard errors against closed-
// form formulas and Monte-Carlo spread, and refusals with their reasons.
#include "calib/solvers/linear_least_squares.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/random.h"

namespace adahrs::calib {
namespace {

using common::Rng;
using ::testing::HasSubstr;

// y = 2 + 3 x + e, x uniform on [0, 10], e ~ N(0, sigma^2).
LinearLeastSquaresProblem Line(Rng& rng, int n, double sigma) {
  LinearLeastSquaresProblem p;
  p.context = "line";
  p.term_names = {"1", "x"};
  p.design.resize(n, 2);
  p.observations.resize(n);
  for (int i = 0; i < n; ++i) {
    const double x = rng.Uniform(0.0, 10.0);
    p.design.row(i) << 1.0, x;
    p.observations[i] = 2.0 + 3.0 * x + sigma * rng.Normal();
  }
  return p;
}

TEST(LinearLeastSquares, LineMatchesClosedForm) {
  Rng rng(11);
  const LinearLeastSquaresProblem p = Line(rng, 50, 0.5);
  const LinearFit fit = SolveLinearLeastSquares(p);
  // Closed form: slope = Sxy / Sxx, se(slope) = s / sqrt(Sxx), s^2 = SSR / (n - 2).
  const Eigen::VectorXd x = p.design.col(1);
  const double x_mean = x.mean();
  const double y_mean = p.observations.mean();
  const double sxx = (x.array() - x_mean).square().sum();
  const double sxy = ((x.array() - x_mean) * (p.observations.array() - y_mean)).sum();
  const double slope = sxy / sxx;
  const double intercept = y_mean - slope * x_mean;
  const double ssr = (p.observations.array() - intercept - slope * x.array()).square().sum();
  const double s = std::sqrt(ssr / 48.0);
  // Both are O(1) double computations on the same data: agreement to 1e-10 relative.
  EXPECT_NEAR(fit.coefficients[1], slope, 1e-10 * std::abs(slope));
  EXPECT_NEAR(fit.coefficients[0], intercept, 1e-10 * std::abs(intercept));
  EXPECT_NEAR(fit.sigma, s, 1e-10 * s);
  EXPECT_NEAR(fit.standard_errors[1], s / std::sqrt(sxx), 1e-10 * s / std::sqrt(sxx));
  EXPECT_EQ(fit.dof, 48);
  EXPECT_EQ(fit.rank, 2);
}

// The standard errors are calibrated: over 400 independent data sets the standardised errors
// z = (beta_hat - beta) / se have unit spread. z follows Student t with 48 dof (sd 1.021); the
// sample sd of 400 values has a relative standard error of ~3.6 %, so [0.90, 1.15] is > 3 sigma.
TEST(LinearLeastSquares, StandardErrorsAreCalibrated) {
  Rng rng(12);
  double sum_z2 = 0.0;
  constexpr int kSets = 400;
  for (int k = 0; k < kSets; ++k) {
    const LinearFit fit = SolveLinearLeastSquares(Line(rng, 50, 0.5));
    const double z = (fit.coefficients[1] - 3.0) / fit.standard_errors[1];
    sum_z2 += z * z;
  }
  const double sd = std::sqrt(sum_z2 / kSets);
  EXPECT_GT(sd, 0.90);
  EXPECT_LT(sd, 1.15);
}

// Balancing weights (equal noise, unequal weights): the sandwich covariance matches the Monte-
// Carlo spread of the slope. 80 % of the points sit in one cluster and get weight 1/cluster size,
// like a thermal soak. 400 sets: the ratio of spreads is within 0.88..1.12 (> 3 sigma of the
// ~3.6 % sampling error of a standard deviation).
TEST(LinearLeastSquares, BalancingWeightsSandwichMatchesMonteCarlo) {
  Rng rng(13);
  constexpr int kSets = 400;
  constexpr int kN = 100;
  double sum_d2 = 0.0;
  double sum_se2 = 0.0;
  for (int k = 0; k < kSets; ++k) {
    LinearLeastSquaresProblem p;
    p.context = "balanced";
    p.term_names = {"1", "x"};
    p.design.resize(kN, 2);
    p.observations.resize(kN);
    p.weights.resize(kN);
    p.weight_kind = WeightKind::kBalancing;
    for (int i = 0; i < kN; ++i) {
      const bool cluster = i < 80;
      const double x = cluster ? rng.Uniform(4.9, 5.1) : rng.Uniform(0.0, 10.0);
      p.design.row(i) << 1.0, x;
      p.observations[i] = 2.0 + 3.0 * x + 0.5 * rng.Normal();
      p.weights[i] = cluster ? 1.0 / 80.0 : 1.0 / 2.0;
    }
    const LinearFit fit = SolveLinearLeastSquares(p);
    sum_d2 += (fit.coefficients[1] - 3.0) * (fit.coefficients[1] - 3.0);
    sum_se2 += fit.standard_errors[1] * fit.standard_errors[1];
  }
  const double ratio = std::sqrt(sum_d2 / sum_se2);
  EXPECT_GT(ratio, 0.88);
  EXPECT_LT(ratio, 1.12);
}

// Known variances, two observations of O + S g and O - S g: se(O) = sqrt(s1^2 + s2^2) / 2 exactly.
TEST(LinearLeastSquares, KnownVarianceExactDesign) {
  LinearLeastSquaresProblem p;
  p.context = "pair";
  p.term_names = {"O", "S"};
  p.design.resize(2, 2);
  p.design << 1.0, 1.0, 1.0, -1.0;
  p.observations.resize(2);
  p.observations << 0.54, 0.46;
  p.weights.resize(2);
  p.weights << 1.0 / (3e-5 * 3e-5), 1.0 / (4e-5 * 4e-5);
  p.error_scale = ErrorScale::kKnownVariance;
  const LinearFit fit = SolveLinearLeastSquares(p);
  EXPECT_NEAR(fit.coefficients[0], 0.50, 1e-14);
  EXPECT_NEAR(fit.coefficients[1], 0.04, 1e-14);
  EXPECT_NEAR(fit.standard_errors[0], 2.5e-5, 1e-18);
  EXPECT_NEAR(fit.standard_errors[1], 2.5e-5, 1e-18);
  EXPECT_EQ(fit.sigma, 1.0);
}

TEST(LinearLeastSquares, RefusesCollinearTermsNamingThem) {
  Rng rng(14);
  LinearLeastSquaresProblem p = Line(rng, 20, 0.1);
  p.context = "collinear";
  p.term_names = {"1", "x", "two_x"};
  p.design.conservativeResize(Eigen::NoChange, 3);
  p.design.col(2) = 2.0 * p.design.col(1);
  try {
    SolveLinearLeastSquares(p);
    FAIL() << "collinear design accepted";
  } catch (const DegenerateDesignError& e) {
    EXPECT_THAT(e.what(), HasSubstr("collinear: design refused: rank 2 of 3 terms"));
    EXPECT_THAT(e.what(), HasSubstr("x"));
    EXPECT_THAT(e.what(), HasSubstr("two_x"));
  }
}

TEST(LinearLeastSquares, RefusesTooFewObservationsAndBadValues) {
  Rng rng(15);
  LinearLeastSquaresProblem p = Line(rng, 2, 0.1);
  EXPECT_THAT([&] { SolveLinearLeastSquares(p); },
              ::testing::ThrowsMessage<DegenerateDesignError>(
                  HasSubstr("2 observations for 2 terms leave no degree of freedom")));
  p = Line(rng, 1, 0.1);
  EXPECT_THAT(
      [&] { SolveLinearLeastSquares(p); },
      ::testing::ThrowsMessage<DegenerateDesignError>(HasSubstr("1 observations for 2 terms")));
  p = Line(rng, 10, 0.1);
  p.observations[7] = std::nan("");
  EXPECT_THAT(
      [&] { SolveLinearLeastSquares(p); },
      ::testing::ThrowsMessage<DegenerateDesignError>(HasSubstr("observation 7 is not finite")));
}

TEST(LinearLeastSquares, RefusesIllConditionedDesign) {
  // x and x + 1e-6 u are distinct but indistinguishable at a condition limit of 1e4.
  Rng rng(16);
  LinearLeastSquaresProblem p = Line(rng, 30, 0.1);
  p.term_names = {"1", "x", "x_nearly"};
  p.design.conservativeResize(Eigen::NoChange, 3);
  for (int i = 0; i < 30; ++i) p.design(i, 2) = p.design(i, 1) + 1e-6 * rng.Normal();
  LeastSquaresOptions options;
  options.max_condition = 1e4;
  EXPECT_THAT([&] { SolveLinearLeastSquares(p, options); },
              ::testing::ThrowsMessage<DegenerateDesignError>(HasSubstr("(limit 1e+04)")));
}

}  // namespace
}  // namespace adahrs::calib
