// Truth tests of the polynomial least-squares driver (FitPolynomial): known polynomials recovered
// from noise-free data, the NIST StRD certified linear-regression results (Wampler1, Wampler3,
// Pontius), standard errors of the raw coefficients against Monte-Carlo spread, weights honoured,
// and refusals with their reasons. No expected value comes from the driver itself.
#include "calib/solvers/polynomial_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/random.h"

namespace adahrs::calib {
namespace {

using common::Rng;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// sum_k c[k] x^k.
double Polynomial(const std::vector<double>& c, double x) {
  double out = 0.0;
  for (size_t k = c.size(); k-- > 0;) out = out * x + c[k];
  return out;
}

// n points evenly spaced over [lo, hi].
std::vector<double> Grid(double lo, double hi, int n) {
  std::vector<double> x;
  for (int i = 0; i < n; ++i) x.push_back(lo + (hi - lo) * i / (n - 1));
  return x;
}

PolynomialFit FitUnivariate(const std::string& context,
                            int degree,
                            const PolynomialObservations& obs,
                            WeightKind weight_kind = WeightKind::kInverseVariance,
                            ErrorScale error_scale = ErrorScale::kResidualVariance,
                            const LeastSquaresOptions& options = {}) {
  return FitPolynomial(
      context, PolynomialBasis::Univariate(degree, "t"), obs, weight_kind, error_scale, options);
}

// ------------------------------------------------------------------------------------------------
// Noise-free data: the generating coefficients come back.

// A thermal-drift-like cubic over -40..85 degC (the span of a thermal soak): the normalised fit
// re-expanded in raw degC gives the generating coefficients. The data are exact to double rounding
// (1e-16 of |z| ~ 3) and the normalised design is well conditioned, so each raw coefficient is
// recovered to 1e-13 of the size of its term at the range edge (|c_k| 85^k).
TEST(PolynomialFit, RecoversKnownCubicFromNoiseFreeData) {
  const std::vector<double> truth = {3.0, -0.05, 2.0e-4, -1.0e-6};
  PolynomialObservations obs;
  obs.x = Grid(-40.0, 85.0, 26);
  for (double t_c : obs.x) obs.z.push_back(Polynomial(truth, t_c));
  const PolynomialFit fit = FitUnivariate("cubic", 3, obs);
  ASSERT_EQ(fit.raw_coefficients.size(), 4);
  for (int k = 0; k < 4; ++k) {
    const double truth_k = truth[static_cast<size_t>(k)];
    EXPECT_NEAR(fit.raw_coefficients[k], truth_k, 1e-13 * std::abs(truth_k) * std::pow(85.0, k))
        << "t^" << k;
  }
  // The fitted box and the scaling follow the range of x: centre 22.5, half-span 62.5.
  EXPECT_EQ(fit.x_min, -40.0);
  EXPECT_EQ(fit.x_max, 85.0);
  EXPECT_DOUBLE_EQ(fit.x_scaling.centre, 22.5);
  EXPECT_DOUBLE_EQ(fit.x_scaling.half_span, 62.5);
  EXPECT_EQ(fit.fit.observations, 26);
  EXPECT_EQ(fit.fit.dof, 22);
  EXPECT_EQ(fit.fit.rank, 4);
  EXPECT_LT(fit.fit.residual_rms, 1e-14);
  // Evaluate (through the normalised coefficients) reproduces the polynomial between the nodes.
  for (double t_c : {-37.3, 0.0, 12.5, 61.1, 84.9}) {
    EXPECT_NEAR(
        fit.Evaluate(PolynomialBasis::Univariate(3, "t"), t_c), Polynomial(truth, t_c), 1e-13);
  }
}

// A bridge surface in ADC-code inputs (x 2.0e6..6.5e6 counts, y 3.1e6..3.6e6 counts), the case the
// normalisation exists for: the raw monomials span 1e20. The generating raw coefficients are set
// so that each term contributes O(0.1..100) at the box corner; each comes back to 1e-8 of its own
// size (the raw re-expansion cancels terms up to ~1e4 times the result; the normalised solve is
// good to ~1e-13).
TEST(PolynomialFit, RecoversKnownSurfaceInAdcCountInputs) {
  const PolynomialBasis basis = PolynomialBasis::ReferenceCubicSurface("x", "y");
  constexpr double kXCornerCnt = 6.5e6;
  constexpr double kYCornerCnt = 3.6e6;
  const std::array<double, 10> term_at_corner = {
      40.0, 90.0, -7.0, 3.0, 0.5, -2.0, 0.8, -0.3, 0.2, -0.6};
  Eigen::VectorXd truth(10);
  for (int k = 0; k < 10; ++k) {
    const Monomial& m = basis.terms()[static_cast<size_t>(k)];
    truth[k] = term_at_corner[static_cast<size_t>(k)] /
               (std::pow(kXCornerCnt, m.x_power) * std::pow(kYCornerCnt, m.y_power));
  }
  Rng rng(31);
  PolynomialObservations obs;
  for (int i = 0; i < 60; ++i) {
    obs.x.push_back(rng.Uniform(2.0e6, 6.5e6));
    obs.y.push_back(rng.Uniform(3.1e6, 3.6e6));
    obs.z.push_back(basis.Row(obs.x.back(), obs.y.back()).dot(truth));
  }
  const PolynomialFit fit = FitPolynomial(
      "surface", basis, obs, WeightKind::kInverseVariance, ErrorScale::kResidualVariance);
  for (int k = 0; k < 10; ++k) {
    EXPECT_NEAR(fit.raw_coefficients[k], truth[k], 1e-8 * std::abs(truth[k]))
        << basis.TermNames()[static_cast<size_t>(k)];
  }
  EXPECT_EQ(fit.y_min, *std::min_element(obs.y.begin(), obs.y.end()));
  EXPECT_EQ(fit.y_max, *std::max_element(obs.y.begin(), obs.y.end()));
  for (size_t i = 0; i < obs.x.size(); i += 7) {
    EXPECT_NEAR(fit.Evaluate(basis, obs.x[i], obs.y[i]), obs.z[i], 1e-11);
  }
}

// With known variances the driver accepts as many points as terms, and the fit is then the
// interpolating polynomial: four points of a cubic give its coefficients.
TEST(PolynomialFit, KnownVarianceInterpolatesWithAsManyPointsAsTerms) {
  const std::vector<double> truth = {-2.0, 0.5, 0.25, -0.125};
  PolynomialObservations obs;
  obs.x = {-3.0, -1.0, 2.0, 5.0};
  for (double x : obs.x) obs.z.push_back(Polynomial(truth, x));
  const PolynomialFit fit = FitUnivariate(
      "interpolant", 3, obs, WeightKind::kInverseVariance, ErrorScale::kKnownVariance);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(fit.raw_coefficients[k], truth[static_cast<size_t>(k)], 1e-14) << "t^" << k;
  }
  EXPECT_EQ(fit.fit.dof, 0);
}

// Extra regressors are fitted as they are, after the basis's terms, and the change of basis leaves
// their coefficient and covariance untouched. z = 1.5 + 0.02 x + 0.7 h + N(0, 0.01^2), 40 points,
// h uniform on [-1, 1] (sd 0.577): se(h) ~ 0.01 / (0.577 sqrt(40)) = 2.7e-3; the bounds on the
// estimates are 4 standard errors.
TEST(PolynomialFit, ExtraColumnsAreFittedAndKeptByTheChangeOfBasis) {
  Rng rng(32);
  PolynomialObservations obs;
  obs.extra_names = {"hysteresis_state"};
  obs.extra_columns.resize(1);
  for (int i = 0; i < 40; ++i) {
    const double x = rng.Uniform(100.0, 300.0);
    const double h = rng.Uniform(-1.0, 1.0);
    obs.x.push_back(x);
    obs.extra_columns[0].push_back(h);
    obs.z.push_back(1.5 + 0.02 * x + 0.7 * h + 0.01 * rng.Normal());
  }
  const PolynomialFit fit = FitUnivariate("with extra", 1, obs);
  ASSERT_EQ(fit.raw_coefficients.size(), 3);
  EXPECT_EQ(fit.raw_coefficients[2], fit.normalised_coefficients[2]);
  EXPECT_EQ(fit.raw_covariance(2, 2), fit.fit.covariance(2, 2));
  EXPECT_NEAR(fit.raw_standard_errors[2], 2.7e-3, 0.7e-3);
  EXPECT_NEAR(fit.raw_coefficients[2], 0.7, 4.0 * fit.raw_standard_errors[2]);
  EXPECT_NEAR(fit.raw_coefficients[1], 0.02, 4.0 * fit.raw_standard_errors[1]);
  EXPECT_NEAR(fit.raw_coefficients[0], 1.5, 4.0 * fit.raw_standard_errors[0]);
}

// ------------------------------------------------------------------------------------------------
// NIST Statistical Reference Datasets, linear least squares
// (https://www.itl.nist.gov/div898/strd/lls/lls.shtml): data and certified values as published.
// Fitted as ordinary (unweighted) least squares with the residual variance, as certified.

// The Wampler data sets: a quintic in x = 0, 1, ..., 20 fitted to the published y.
PolynomialFit FitWampler(const std::string& name, const std::vector<double>& y) {
  PolynomialObservations obs;
  obs.x = Grid(0.0, 20.0, 21);
  obs.z = y;
  return FitUnivariate(name, 5, obs);
}

// Wampler1 (higher difficulty): y = 1 + x + x^2 + x^3 + x^4 + x^5 exactly at x = 0..20; certified
// estimates 1, standard errors 0, residual standard deviation 0. y reaches 3.4e6, so double
// rounding of the normalised solve (~1e-16 of 3.4e6 times the condition) is ~1e-9 absolute in the
// raw coefficients after the alternating re-expansion: 8 digits are required of each.
TEST(PolynomialFitNist, Wampler1CertifiedValues) {
  const PolynomialFit fit =
      FitWampler("Wampler1", {1,      6,      63,      364,     1365,    3906,    9331,
                              19608,  37449,  66430,   111111,  177156,  271453,  402234,
                              579195, 813616, 1118481, 1508598, 2000719, 2613660, 3368421});
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(fit.raw_coefficients[k], 1.0, 1e-8) << "B" << k;
    EXPECT_LT(fit.raw_standard_errors[k], 1e-8) << "B" << k;
  }
  EXPECT_LT(fit.fit.sigma, 1e-8);
}

// Wampler3 (higher difficulty): Wampler1 plus large integer noise. Certified estimates all 1, and
// the standard errors and residual standard deviation below (15 significant digits). Required:
// estimates to 1e-8 absolute (as Wampler1: the noise is ~2000, the rounding the same), standard
// errors and residual SD to 1e-12 relative (they depend on the design and the residuals only, both
// well conditioned: the equilibrated design's condition number is 25).
TEST(PolynomialFitNist, Wampler3CertifiedValues) {
  const PolynomialFit fit =
      FitWampler("Wampler3", {760,    -2042,  2111,    -1684,   3888,    1858,    11379,
                              17560,  39287,  64382,   113159,  175108,  273291,  400186,
                              581243, 811568, 1121004, 1506550, 2002767, 2611612, 3369180});
  const std::vector<double> certified_se = {2152.32624678170,
                                            2363.55173469681,
                                            779.343524331583,
                                            101.475507550350,
                                            5.64566512170752,
                                            0.112324854679312};
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(fit.raw_coefficients[k], 1.0, 1e-8) << "B" << k;
    EXPECT_NEAR(fit.raw_standard_errors[k],
                certified_se[static_cast<size_t>(k)],
                1e-12 * certified_se[static_cast<size_t>(k)])
        << "B" << k;
  }
  EXPECT_NEAR(fit.fit.sigma, 2360.14502379268, 1e-12 * 2360.14502379268);
  EXPECT_EQ(fit.fit.dof, 15);
}

// Pontius (average difficulty): a load-cell calibration, deflection against load 150,000 ..
// 3,000,000 lb, each load twice: a quadratic in a large raw input, like the ADC-code fits. The
// raw coefficients span 1e-3 .. 1e-14. Required: estimates, standard errors and the residual
// standard deviation to 1e-11 relative (the intercept, the worst, cancels terms ~100 times its
// size in the re-expansion from the normalised load).
TEST(PolynomialFitNist, PontiusCertifiedValues) {
  const std::vector<double> deflection = {
      .11019,  .21956,  .32949,  .43899,  .54803,  .65694,  .76562,  .87487,  .98292,  1.09146,
      1.20001, 1.30822, 1.41599, 1.52399, 1.63194, 1.73947, 1.84646, 1.95392, 2.06128, 2.16844,
      .11052,  .22018,  .32939,  .43886,  .54798,  .65739,  .76596,  .87474,  .98300,  1.09150,
      1.20004, 1.30818, 1.41613, 1.52408, 1.63159, 1.73965, 1.84696, 1.95445, 2.06177, 2.16829};
  const std::vector<double> certified = {
      0.673565789473684E-03, 0.732059160401003E-06, -0.316081871345029E-14};
  const std::vector<double> certified_se = {
      0.107938612033077E-03, 0.157817399981659E-09, 0.486652849992036E-16};
  PolynomialObservations obs;
  for (int i = 0; i < 40; ++i) obs.x.push_back(150000.0 * (1 + i % 20));  // load, lb
  obs.z = deflection;
  const PolynomialFit fit = FitUnivariate("Pontius", 2, obs);
  for (int k = 0; k < 3; ++k) {
    const auto s = static_cast<size_t>(k);
    EXPECT_NEAR(fit.raw_coefficients[k], certified[s], 1e-11 * std::abs(certified[s])) << "B" << k;
    EXPECT_NEAR(fit.raw_standard_errors[k], certified_se[s], 1e-11 * certified_se[s]) << "B" << k;
  }
  EXPECT_NEAR(fit.fit.sigma, 0.205177424076185E-03, 1e-11 * 0.205177424076185E-03);
}

// ------------------------------------------------------------------------------------------------
// Standard errors against Monte-Carlo spread, and weights.

// 2000 sets: the sample standard deviation of 2000 normal values has a relative standard error of
// 1/sqrt(4000) = 1.6 %, and the mean of 2000 residual variances adds < 0.6 %: bounds of +-6 % are
// > 3.5 standard errors, while a wrong covariance map (Cov instead of T Cov T') or the wrong
// degrees of freedom (n instead of n - p: 22 % for the 12-point case) falls far outside.
constexpr int kMonteCarloSets = 2000;
constexpr double kSpreadTolerance = 0.06;

// A cubic drift over -40..85 degC observed at `t_c` with independent noise of `noise_sd` each.
struct NoisyCubic {
  std::vector<double> t_c;
  std::vector<double> noise_sd;
  std::vector<double> weights;  ///< empty for all 1
  WeightKind weight_kind = WeightKind::kInverseVariance;
  ErrorScale error_scale = ErrorScale::kResidualVariance;
};

// Over kMonteCarloSets independent data sets, the observed spread of each raw coefficient about
// the truth matches the root-mean-square standard error the fit reports.
void ExpectStandardErrorsMatchSpread(const NoisyCubic& design, uint64_t seed) {
  const std::vector<double> truth = {3.0, -0.05, 2.0e-4, -1.0e-6};
  Rng rng(seed);
  Eigen::VectorXd sum_d2 = Eigen::VectorXd::Zero(4);
  Eigen::VectorXd sum_se2 = Eigen::VectorXd::Zero(4);
  for (int set = 0; set < kMonteCarloSets; ++set) {
    PolynomialObservations obs;
    obs.x = design.t_c;
    obs.weights = design.weights;
    for (size_t i = 0; i < design.t_c.size(); ++i) {
      obs.z.push_back(Polynomial(truth, design.t_c[i]) + design.noise_sd[i] * rng.Normal());
    }
    const PolynomialFit fit =
        FitUnivariate("monte carlo", 3, obs, design.weight_kind, design.error_scale);
    sum_d2 +=
        (fit.raw_coefficients - Eigen::Map<const Eigen::VectorXd>(truth.data(), 4)).cwiseAbs2();
    sum_se2 += fit.raw_standard_errors.cwiseAbs2();
  }
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(std::sqrt(sum_d2[k] / sum_se2[k]), 1.0, kSpreadTolerance) << "t^" << k;
  }
}

// Unweighted, residual variance: 12 points with noise 0.02; the raw standard errors come through
// the change of basis.
TEST(PolynomialFitMonteCarlo, ResidualVarianceStandardErrorsMatchSpread) {
  NoisyCubic design;
  design.t_c = Grid(-40.0, 85.0, 12);
  design.noise_sd.assign(12, 0.02);
  ExpectStandardErrorsMatchSpread(design, 41);
}

// Inverse-variance weights with known variances: noise standard deviation rising from 0.005 to
// 0.05 across the range, w_i = 1 / sd_i^2. The reported standard errors are then exact (no
// estimated scale) and must match the spread; ignoring the weights would report the errors of a
// unit variance, ~20..200 times too large.
TEST(PolynomialFitMonteCarlo, InverseVarianceWeightsAreHonoured) {
  NoisyCubic design;
  design.t_c = Grid(-40.0, 85.0, 20);
  for (int i = 0; i < 20; ++i) {
    design.noise_sd.push_back(0.005 + 0.045 * i / 19.0);
    design.weights.push_back(1.0 / (design.noise_sd.back() * design.noise_sd.back()));
  }
  design.error_scale = ErrorScale::kKnownVariance;
  ExpectStandardErrorsMatchSpread(design, 42);
}

// Balancing weights (equal noise 0.02; a thermal soak's 30 points at 20..25 degC weighted down to
// the 10 spread ones): the sandwich covariance carried to the raw coefficients matches the spread.
TEST(PolynomialFitMonteCarlo, BalancingWeightsStandardErrorsMatchSpread) {
  NoisyCubic design;
  design.t_c = Grid(-40.0, 85.0, 10);
  design.weights.assign(10, 1.0 / 10.0);
  for (double t : Grid(20.0, 25.0, 30)) {
    design.t_c.push_back(t);
    design.weights.push_back(1.0 / 30.0);
  }
  design.noise_sd.assign(40, 0.02);
  design.weight_kind = WeightKind::kBalancing;
  ExpectStandardErrorsMatchSpread(design, 43);
}

// Weighted constant (degree 0): the estimate is the weighted mean sum w z / sum w, with standard
// error 1 / sqrt(sum w) for known variances and sqrt(sum w r^2 / (n - 1) / sum w) otherwise.
TEST(PolynomialFit, WeightedConstantIsTheWeightedMean) {
  Rng rng(44);
  PolynomialObservations obs;
  double sum_w = 0.0;
  double sum_wz = 0.0;
  for (int i = 0; i < 15; ++i) {
    obs.x.push_back(i);
    obs.z.push_back(rng.Uniform(-1.0, 1.0));
    obs.weights.push_back(rng.Uniform(0.5, 20.0));
    sum_w += obs.weights.back();
    sum_wz += obs.weights.back() * obs.z.back();
  }
  const double mean = sum_wz / sum_w;
  double sum_wr2 = 0.0;
  for (size_t i = 0; i < obs.z.size(); ++i) {
    sum_wr2 += obs.weights[i] * (obs.z[i] - mean) * (obs.z[i] - mean);
  }
  const PolynomialFit known =
      FitUnivariate("mean", 0, obs, WeightKind::kInverseVariance, ErrorScale::kKnownVariance);
  EXPECT_NEAR(known.raw_coefficients[0], mean, 1e-15);
  EXPECT_NEAR(known.raw_standard_errors[0], 1.0 / std::sqrt(sum_w), 1e-15);
  const PolynomialFit estimated = FitUnivariate("mean", 0, obs);
  EXPECT_NEAR(estimated.raw_coefficients[0], mean, 1e-15);
  EXPECT_NEAR(estimated.raw_standard_errors[0], std::sqrt(sum_wr2 / 14.0 / sum_w), 1e-15);
}

// An integer weight m is the same as the observation repeated m times (same x range, so the same
// scaling): equal coefficients and, with known variances, equal covariance.
TEST(PolynomialFit, IntegerWeightEqualsRepeatedObservation) {
  Rng rng(45);
  PolynomialObservations weighted;
  PolynomialObservations repeated;
  for (int i = 0; i < 12; ++i) {
    const double t = rng.Uniform(-40.0, 85.0);
    const double z = 1.0 + 0.01 * t - 1e-4 * t * t + 0.05 * rng.Normal();
    const int m = 1 + i % 3;
    weighted.x.push_back(t);
    weighted.z.push_back(z);
    weighted.weights.push_back(m);
    for (int j = 0; j < m; ++j) {
      repeated.x.push_back(t);
      repeated.z.push_back(z);
    }
  }
  const PolynomialFit a = FitUnivariate(
      "weighted", 2, weighted, WeightKind::kInverseVariance, ErrorScale::kKnownVariance);
  const PolynomialFit b = FitUnivariate(
      "repeated", 2, repeated, WeightKind::kInverseVariance, ErrorScale::kKnownVariance);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(
        a.raw_coefficients[k], b.raw_coefficients[k], 1e-12 * std::abs(b.raw_coefficients[k]))
        << "t^" << k;
    EXPECT_NEAR(
        a.raw_standard_errors[k], b.raw_standard_errors[k], 1e-12 * b.raw_standard_errors[k])
        << "t^" << k;
  }
}

// ------------------------------------------------------------------------------------------------
// Refusals: DegenerateDesignError (std::invalid_argument) with the context first and the reason.

PolynomialObservations Cubic(int n) {
  PolynomialObservations obs;
  obs.x = Grid(-40.0, 85.0, n);
  for (double t : obs.x) obs.z.push_back(Polynomial({3.0, -0.05, 2.0e-4, -1.0e-6}, t));
  return obs;
}

TEST(PolynomialFitRefusal, TooFewPoints) {
  EXPECT_THAT([] { FitUnivariate("cubic of az1", 3, Cubic(3)); },
              ThrowsMessage<DegenerateDesignError>(
                  HasSubstr("cubic of az1: design refused: 3 observations for 4 terms")));
  EXPECT_THAT([] { FitUnivariate("cubic of az1", 3, Cubic(4)); },
              ThrowsMessage<DegenerateDesignError>(
                  HasSubstr("cubic of az1: design refused: 4 observations for 4 terms leave no "
                            "degree of freedom")));
  EXPECT_THAT([] { FitUnivariate("cubic of az1", 3, PolynomialObservations{}); },
              ThrowsMessage<DegenerateDesignError>(HasSubstr("0 observations for 4 terms")));
}

// Ten points at one temperature cannot fix a slope: the columns t, t^2, t^3 vanish (the span is
// zero, so the scaling keeps half-span 1 and the design check, not a division, reports it).
TEST(PolynomialFitRefusal, InputThatDoesNotVary) {
  PolynomialObservations obs;
  obs.x.assign(10, 25.0);
  obs.z.assign(10, 1.0);
  EXPECT_THAT(
      [&] { FitUnivariate("soak", 3, obs); },
      ThrowsMessage<DegenerateDesignError>(HasSubstr("soak: design refused: rank 1 of 4 terms")));
}

// Two distinct temperatures for a quadratic: in normalised inputs u = +-1, so u^2 = 1 repeats the
// constant and the message names that combination.
TEST(PolynomialFitRefusal, RankDeficientNamesTheNullCombination) {
  PolynomialObservations obs;
  for (int i = 0; i < 8; ++i) {
    obs.x.push_back(i % 2 == 0 ? -20.0 : 60.0);
    obs.z.push_back(0.1 * i);
  }
  EXPECT_THAT([&] { FitUnivariate("two soaks", 2, obs); },
              ThrowsMessage<DegenerateDesignError>(
                  AllOf(HasSubstr("two soaks: design refused: rank 2 of 3 terms"),
                        HasSubstr(" 1"),
                        HasSubstr("t^2"))));
}

// A surface basis given no y: the y columns are all zero and the design is refused.
TEST(PolynomialFitRefusal, SurfaceWithoutSecondInput) {
  PolynomialObservations obs = Cubic(30);
  EXPECT_THAT(
      [&] {
        FitPolynomial("surface",
                      PolynomialBasis::ReferenceCubicSurface("ps", "pt"),
                      obs,
                      WeightKind::kInverseVariance,
                      ErrorScale::kResidualVariance);
      },
      ThrowsMessage<DegenerateDesignError>(HasSubstr("surface: design refused: rank 4 of 10")));
}

// An extra column that repeats a basis term is refused and named.
TEST(PolynomialFitRefusal, ExtraColumnCollinearWithTheBasis) {
  PolynomialObservations obs = Cubic(20);
  obs.extra_names = {"offset_state"};
  obs.extra_columns = {std::vector<double>(20, 2.0)};
  EXPECT_THAT(
      [&] { FitUnivariate("with extra", 3, obs); },
      ThrowsMessage<DegenerateDesignError>(AllOf(
          HasSubstr("with extra: design refused: rank 4 of 5 terms"), HasSubstr("offset_state"))));
}

TEST(PolynomialFitRefusal, NonFiniteValueOrNonPositiveWeight) {
  PolynomialObservations obs = Cubic(10);
  obs.z[6] = std::nan("");
  EXPECT_THAT([&] { FitUnivariate("cubic", 3, obs); },
              ThrowsMessage<DegenerateDesignError>(
                  HasSubstr("cubic: design refused: observation 6 is not finite or has a weight "
                            "<= 0")));
  obs = Cubic(10);
  obs.weights.assign(10, 1.0);
  obs.weights[3] = 0.0;
  EXPECT_THAT([&] { FitUnivariate("cubic", 3, obs); },
              ThrowsMessage<DegenerateDesignError>(HasSubstr("observation 3 is not finite")));
  obs.weights[3] = -1.0;
  EXPECT_THAT([&] { FitUnivariate("cubic", 3, obs); },
              ThrowsMessage<DegenerateDesignError>(HasSubstr("observation 3 is not finite")));
}

// A degree-8 fit over 40 evenly spaced points has an equilibrated condition number of ~300: within
// the default limit (1e8), refused under a limit of 100 given in the options.
TEST(PolynomialFitRefusal, IllConditionedBeyondTheGivenLimit) {
  EXPECT_NO_THROW(FitUnivariate("degree 8", 8, Cubic(40)));
  LeastSquaresOptions options;
  options.max_condition = 100.0;
  EXPECT_THAT(
      [&] {
        FitUnivariate("degree 8",
                      8,
                      Cubic(40),
                      WeightKind::kInverseVariance,
                      ErrorScale::kResidualVariance,
                      options);
      },
      ThrowsMessage<DegenerateDesignError>(AllOf(
          HasSubstr("degree 8: design refused: rank 9 of 9 terms"), HasSubstr("(limit 100)"))));
}

// Inconsistent inputs are a caller's bug: std::invalid_argument naming the lengths.
TEST(PolynomialFitRefusal, InconsistentLengths) {
  PolynomialObservations obs = Cubic(10);
  obs.z.pop_back();
  EXPECT_THAT([&] { FitUnivariate("cubic", 3, obs); },
              ThrowsMessage<std::invalid_argument>(
                  HasSubstr("cubic: 10 x, 0 y, 9 z and 0 weights differ in length")));
  obs = Cubic(10);
  obs.weights.assign(9, 1.0);
  EXPECT_THAT([&] { FitUnivariate("cubic", 3, obs); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("9 weights differ in length")));
  obs = Cubic(10);
  obs.y.assign(3, 0.0);
  EXPECT_THAT([&] { FitUnivariate("cubic", 3, obs); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("10 x, 3 y, 10 z")));
  obs = Cubic(10);
  obs.extra_columns = {std::vector<double>(10, 0.0)};
  EXPECT_THAT([&] { FitUnivariate("cubic", 3, obs); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("1 extra columns but 0 names")));
  obs.extra_names = {"h"};
  obs.extra_columns[0].pop_back();
  EXPECT_THAT([&] { FitUnivariate("cubic", 3, obs); },
              ThrowsMessage<std::invalid_argument>(
                  HasSubstr("extra column h has 9 values for 10 observations")));
}

}  // namespace
}  // namespace adahrs::calib
