// Generic weighted linear least-squares driver (Eigen) for the calibration models: it knows nothing
// about sensors. A model supplies the design matrix (one row per observation, one column per term,
// named for messages), the observations and optional weights; the driver returns the estimate with
// its covariance and standard errors, and refuses a degenerate design with the reason.
//
// Method (derivation in docs/calibration-solvers.md, "The driver"):
//   minimise sum_i w_i (y_i - a_i . beta)^2.
//   Columns are first equilibrated (each scaled to unit 2-norm of sqrt(w) a_j) so that the rank and
//   condition tests do not depend on the units of the terms; the scaled problem is solved by a
//   Householder QR, and the singular values of its R factor give rank and condition number.
//   Covariance, by the meaning of the weights:
//     kInverseVariance: var(e_i) = sigma^2 / w_i  ->  Cov = sigma^2 (A'WA)^-1, with
//       sigma^2 = 1 when the variances are known (kKnownVariance), else
//       sigma^2 = sum w_i r_i^2 / (n - p) (kResidualVariance);
//     kBalancing: equal noise variance sigma^2, weights only re-balance the design (e.g. every
//       temperature band weighs the same)  ->  Cov = sigma^2 (A'WA)^-1 (A'W^2A) (A'WA)^-1 (the
//       sandwich form), sigma^2 = sum r_i^2 / (n - p).
//   Standard errors are the square roots of the covariance diagonal.
// Refusals (DegenerateDesignError, naming the context): fewer observations than terms, no degree of
// freedom when the variance must come from the residuals, a non-finite or negative input, numerical
// rank below the number of terms, or condition number above the limit; the message names the
// near-null combination of terms (the right singular vector of the smallest singular value).
// Not modelled: correlated observation errors (per-packet samples of a slowly drifting sensor are
// correlated, so residual-variance standard errors are then optimistic; a caller that knows the
// covariance whitens its rows first, as the joint IMU strategy does), robust losses, nonlinear
// models.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace adahrs::calib {

/// A design the driver refuses, with the reason in what().
class DegenerateDesignError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// What the weights mean (see the header comment).
enum class WeightKind {
  kInverseVariance,  ///< w_i = sigma^2 / var(e_i); empty weights mean all 1
  kBalancing,        ///< equal noise; w_i only re-balances the design
};

/// Where the residual scale sigma^2 comes from.
enum class ErrorScale {
  kResidualVariance,  ///< estimated from the residuals (needs n > p)
  kKnownVariance,     ///< sigma^2 = 1: the inverse-variance weights are exact
};

struct LinearLeastSquaresProblem {
  std::string context;                  ///< e.g. "thermal fit of az1", leads every message
  std::vector<std::string> term_names;  ///< one per column
  Eigen::MatrixXd design;               ///< n x p
  Eigen::VectorXd observations;         ///< n
  Eigen::VectorXd weights;              ///< n, or empty for all 1
  WeightKind weight_kind = WeightKind::kInverseVariance;
  ErrorScale error_scale = ErrorScale::kResidualVariance;
};

struct LeastSquaresOptions {
  /// Largest accepted condition number of the column-equilibrated, weighted design.
  double max_condition = 1e8;
  /// Singular values below this fraction of the largest count as zero for the rank.
  double rank_tolerance = 1e-12;
};

/// The outcome of a fit: estimate, uncertainty and the design diagnostics.
struct LinearFit {
  Eigen::VectorXd coefficients;     ///< p
  Eigen::MatrixXd covariance;       ///< p x p
  Eigen::VectorXd standard_errors;  ///< p, sqrt(diag(covariance))
  double sigma = 0.0;               ///< residual scale used (1 for kKnownVariance)
  double residual_rms = 0.0;        ///< unweighted rms of y - A beta, observation units
  double max_abs_residual = 0.0;    ///< observation units
  int observations = 0;             ///< n
  int dof = 0;                      ///< n - p
  int rank = 0;                     ///< numerical rank (== p for an accepted design)
  double condition_number = 0.0;    ///< of the equilibrated weighted design
};

/// Solves `problem`; throws DegenerateDesignError with the context and reason if it is refused.
LinearFit SolveLinearLeastSquares(const LinearLeastSquaresProblem& problem,
                                  const LeastSquaresOptions& options = {});

}  // namespace adahrs::calib
