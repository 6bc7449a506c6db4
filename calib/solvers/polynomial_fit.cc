#include "calib/solvers/polynomial_fit.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

namespace adahrs::calib {

double PolynomialFit::Evaluate(const PolynomialBasis& basis, double x, double y) const {
  return basis.Evaluate(
      normalised_coefficients.head(basis.size()), x_scaling.Normalise(x), y_scaling.Normalise(y));
}

PolynomialFit FitPolynomial(const std::string& context,
                            const PolynomialBasis& basis,
                            const PolynomialObservations& obs,
                            WeightKind weight_kind,
                            ErrorScale error_scale,
                            const LeastSquaresOptions& options) {
  const size_t n = obs.x.size();
  const bool bivariate = !obs.y.empty();
  if (obs.z.size() != n || (bivariate && obs.y.size() != n) ||
      (!obs.weights.empty() && obs.weights.size() != n)) {
    throw std::invalid_argument(fmt::format("{}: {} x, {} y, {} z and {} weights differ in length",
                                            context,
                                            n,
                                            obs.y.size(),
                                            obs.z.size(),
                                            obs.weights.size()));
  }
  if (obs.extra_names.size() != obs.extra_columns.size()) {
    throw std::invalid_argument(fmt::format("{}: {} extra columns but {} names",
                                            context,
                                            obs.extra_columns.size(),
                                            obs.extra_names.size()));
  }
  for (size_t c = 0; c < obs.extra_columns.size(); ++c) {
    if (obs.extra_columns[c].size() != n) {
      throw std::invalid_argument(
          fmt::format("{}: extra column {} has {} values for {} observations",
                      context,
                      obs.extra_names[c],
                      obs.extra_columns[c].size(),
                      n));
    }
  }
  const Eigen::Index terms = basis.size();
  const Eigen::Index extras = static_cast<Eigen::Index>(obs.extra_columns.size());
  PolynomialFit out;
  if (n > 0) {
    const auto [x_lo, x_hi] = std::minmax_element(obs.x.begin(), obs.x.end());
    out.x_min = *x_lo;
    out.x_max = *x_hi;
    if (bivariate) {
      const auto [y_lo, y_hi] = std::minmax_element(obs.y.begin(), obs.y.end());
      out.y_min = *y_lo;
      out.y_max = *y_hi;
      out.y_scaling = InputScaling::FromRange(out.y_min, out.y_max);
    }
    out.x_scaling = InputScaling::FromRange(out.x_min, out.x_max);
  }

  LinearLeastSquaresProblem problem;
  problem.context = context;
  problem.term_names = basis.TermNames();
  problem.term_names.insert(
      problem.term_names.end(), obs.extra_names.begin(), obs.extra_names.end());
  problem.design.resize(static_cast<Eigen::Index>(n), terms + extras);
  problem.observations.resize(static_cast<Eigen::Index>(n));
  for (size_t i = 0; i < n; ++i) {
    const double v = bivariate ? out.y_scaling.Normalise(obs.y[i]) : 0.0;
    const auto row = static_cast<Eigen::Index>(i);
    problem.design.row(row).head(terms) = basis.Row(out.x_scaling.Normalise(obs.x[i]), v);
    for (Eigen::Index c = 0; c < extras; ++c) {
      problem.design(row, terms + c) = obs.extra_columns[static_cast<size_t>(c)][i];
    }
    problem.observations[static_cast<Eigen::Index>(i)] = obs.z[i];
  }
  if (!obs.weights.empty()) {
    problem.weights =
        Eigen::Map<const Eigen::VectorXd>(obs.weights.data(), static_cast<Eigen::Index>(n));
  }
  problem.weight_kind = weight_kind;
  problem.error_scale = error_scale;

  out.fit = SolveLinearLeastSquares(problem, options);
  out.normalised_coefficients = out.fit.coefficients;
  Eigen::MatrixXd t = Eigen::MatrixXd::Identity(terms + extras, terms + extras);
  t.topLeftCorner(terms, terms) = basis.NormalisedToRaw(out.x_scaling, out.y_scaling);
  out.raw_coefficients = t * out.normalised_coefficients;
  out.raw_covariance = t * out.fit.covariance * t.transpose();
  out.raw_standard_errors = out.raw_covariance.diagonal().cwiseSqrt();
  return out;
}

}  // namespace adahrs::calib
