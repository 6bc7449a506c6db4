// Generic weighted linear least-squares driver (Eigen) for the calibration models: it knows nothing
// about sensors. A model supplies the design matrix (one row per observation, one column per named
// term), the observations and optional weights; the driver minimises sum_i w_i (y_i - a_i . beta)^2
// by Householder QR on equilibrated columns and returns the estimate with its covariance
// (inverse-variance weights with known or residual variance, or balancing weights with the
// sandwich form), standard errors, rank and condition number. A degenerate design is refused
// (DegenerateDesignError) naming the near-null combination of terms.
// Units: those of the caller's rows.
// Derivation and refusals: docs/calibration-solvers.md ("The driver").
// Left out: correlated observation errors (a caller that knows the covariance whitens its rows
// first), robust losses, nonlinear models.
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
