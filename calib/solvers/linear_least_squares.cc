#include "calib/solvers/linear_least_squares.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace adahrs::calib {
namespace {

[[noreturn]] void Refuse(const LinearLeastSquaresProblem& problem, const std::string& reason) {
  throw DegenerateDesignError(fmt::format("{}: design refused: {}", problem.context, reason));
}

// The terms that dominate a near-null direction v of the equilibrated design, e.g.
// "+0.707 y -0.707 y^2": the combination of columns that the data cannot tell from zero.
std::string NullCombination(const std::vector<std::string>& names, const Eigen::VectorXd& v) {
  const double largest = v.cwiseAbs().maxCoeff();
  std::string out;
  for (Eigen::Index j = 0; j < v.size(); ++j) {
    if (std::abs(v[j]) < 0.1 * largest) continue;
    out += fmt::format("{}{:+.3f} {}", out.empty() ? "" : " ", v[j], names[j]);
  }
  return out;
}

void CheckInputs(const LinearLeastSquaresProblem& problem) {
  const Eigen::Index n = problem.design.rows();
  const Eigen::Index p = problem.design.cols();
  if (static_cast<Eigen::Index>(problem.term_names.size()) != p ||
      problem.observations.size() != n ||
      (problem.weights.size() != 0 && problem.weights.size() != n)) {
    throw std::invalid_argument(fmt::format(
        "{}: inconsistent problem: design {}x{}, {} term names, {} observations, {} weights",
        problem.context,
        n,
        p,
        problem.term_names.size(),
        problem.observations.size(),
        problem.weights.size()));
  }
  if (p == 0) Refuse(problem, "no terms");
  for (Eigen::Index i = 0; i < n; ++i) {
    const double w = problem.weights.size() == 0 ? 1.0 : problem.weights[i];
    if (!problem.design.row(i).allFinite() || !std::isfinite(problem.observations[i]) ||
        !std::isfinite(w) || w <= 0.0) {
      Refuse(problem, fmt::format("observation {} is not finite or has a weight <= 0", i));
    }
  }
  if (n < p) {
    Refuse(problem, fmt::format("{} observations for {} terms", n, p));
  }
  if (n == p && problem.error_scale == ErrorScale::kResidualVariance) {
    Refuse(problem,
           fmt::format("{} observations for {} terms leave no degree of freedom for the "
                       "residual variance",
                       n,
                       p));
  }
}

}  // namespace

LinearFit SolveLinearLeastSquares(const LinearLeastSquaresProblem& problem,
                                  const LeastSquaresOptions& options) {
  CheckInputs(problem);
  const Eigen::Index n = problem.design.rows();
  const Eigen::Index p = problem.design.cols();
  const Eigen::VectorXd w =
      problem.weights.size() == 0 ? Eigen::VectorXd::Ones(n) : problem.weights;
  const Eigen::VectorXd sqrt_w = w.cwiseSqrt();

  // Equilibrate: A_s = sqrt(W) A D, D = diag(1 / ||sqrt(W) a_j||).
  Eigen::MatrixXd scaled = sqrt_w.asDiagonal() * problem.design;
  Eigen::VectorXd d(p);
  for (Eigen::Index j = 0; j < p; ++j) {
    const double norm = scaled.col(j).norm();
    d[j] = norm > 0.0 ? 1.0 / norm : 1.0;
    scaled.col(j) *= d[j];
  }
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(scaled);
  const Eigen::MatrixXd r = qr.matrixQR().topRows(p).triangularView<Eigen::Upper>();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(r, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  int rank = 0;
  for (Eigen::Index j = 0; j < p; ++j) rank += s[j] > options.rank_tolerance * s[0] ? 1 : 0;
  const double condition =
      s[p - 1] > 0.0 ? s[0] / s[p - 1] : std::numeric_limits<double>::infinity();
  if (rank < p || !(condition <= options.max_condition)) {
    Refuse(problem,
           fmt::format("rank {} of {} terms, condition number {:.3g} (limit {:.3g}); near-null "
                       "combination of the normalised terms: {}",
                       rank,
                       p,
                       condition,
                       options.max_condition,
                       NullCombination(problem.term_names, svd.matrixV().col(p - 1))));
  }

  const Eigen::VectorXd beta_scaled = qr.solve(sqrt_w.cwiseProduct(problem.observations));
  LinearFit fit;
  fit.coefficients = d.cwiseProduct(beta_scaled);
  const Eigen::VectorXd residuals = problem.observations - problem.design * fit.coefficients;

  // (A_s' A_s)^-1 = R^-1 R^-T.
  const Eigen::MatrixXd r_inv =
      r.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
  const Eigen::MatrixXd normal_inv_scaled = r_inv * r_inv.transpose();

  fit.observations = static_cast<int>(n);
  fit.dof = static_cast<int>(n - p);
  fit.rank = rank;
  fit.condition_number = condition;
  fit.residual_rms = std::sqrt(residuals.squaredNorm() / static_cast<double>(n));
  fit.max_abs_residual = residuals.cwiseAbs().maxCoeff();

  Eigen::MatrixXd cov_scaled;
  double sigma2 = 1.0;
  if (problem.weight_kind == WeightKind::kInverseVariance) {
    if (problem.error_scale == ErrorScale::kResidualVariance) {
      sigma2 = w.dot(residuals.cwiseAbs2()) / fit.dof;
    }
    cov_scaled = sigma2 * normal_inv_scaled;
  } else {
    if (problem.error_scale == ErrorScale::kResidualVariance) {
      sigma2 = residuals.squaredNorm() / fit.dof;
    }
    // Sandwich: B = W A D = sqrt(W) A_s; (A'WA)^-1 (A'W^2A) (A'WA)^-1 in scaled coordinates.
    const Eigen::MatrixXd b = sqrt_w.asDiagonal() * scaled;
    cov_scaled = sigma2 * normal_inv_scaled * (b.transpose() * b) * normal_inv_scaled;
  }
  fit.sigma = std::sqrt(sigma2);
  fit.covariance = d.asDiagonal() * cov_scaled * d.asDiagonal();
  fit.standard_errors = fit.covariance.diagonal().cwiseSqrt();
  return fit;
}

}  // namespace adahrs::calib
