// Least-squares fit of a polynomial basis (polynomial_basis.h) in normalised inputs, reported in
// both the normalised and the raw inputs with the covariance carried through the exact change of
// basis (Cov_raw = T Cov T'). The thermal, gyro and air-data models are thin layers over this.
// Inputs are plain vectors of (x, y, z) observations; y is ignored by a univariate basis.
// Extra regressors (columns that are not monomials of x and y, e.g. a hysteresis state) may be
// appended: they are fitted as they are, after the basis's terms, and the change of basis leaves
// them unchanged.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "calib/solvers/linear_least_squares.h"
#include "calib/solvers/polynomial_basis.h"

namespace adahrs::calib {

struct PolynomialObservations {
  std::vector<double> x;
  std::vector<double> y;                           ///< empty for a univariate basis
  std::vector<double> z;                           ///< the fitted quantity
  std::vector<double> weights;                     ///< empty for all 1
  std::vector<std::vector<double>> extra_columns;  ///< each of the observations' length
  std::vector<std::string> extra_names;            ///< one per extra column, for messages
};

struct PolynomialFit {
  InputScaling x_scaling;                   ///< from the range of x
  InputScaling y_scaling;                   ///< from the range of y (identity when univariate)
  Eigen::VectorXd normalised_coefficients;  ///< in u = x_scaling.Normalise(x), v likewise; then
                                            ///< the extra columns' coefficients
  Eigen::VectorXd raw_coefficients;         ///< in raw x, y; then the extra columns'
  Eigen::MatrixXd raw_covariance;
  Eigen::VectorXd raw_standard_errors;
  double x_min = 0.0, x_max = 0.0, y_min = 0.0, y_max = 0.0;  ///< the fitted input box
  LinearFit fit;  ///< the normalised fit and its diagnostics

  /// Evaluates the basis's part at raw inputs through the normalised coefficients (the
  /// well-conditioned form); extra columns are not included.
  double Evaluate(const PolynomialBasis& basis, double x, double y = 0.0) const;
};

/// Fits `basis` to `observations`; throws DegenerateDesignError (context first) when refused.
PolynomialFit FitPolynomial(const std::string& context,
                            const PolynomialBasis& basis,
                            const PolynomialObservations& observations,
                            WeightKind weight_kind,
                            ErrorScale error_scale,
                            const LeastSquaresOptions& options = {});

}  // namespace adahrs::calib
