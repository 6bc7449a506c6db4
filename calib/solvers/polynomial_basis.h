// Polynomial bases in one or two inputs (monomials x^i y^j) shared by the calibration models: the
// design row of an observation, evaluation, and the exact change of basis from normalised inputs
// to the raw inputs the firmware constants use.
//
// The models fit in normalised inputs u = (x - c_x) / s_x, v = (y - c_y) / s_y (each input's range
// mapped onto [-1, 1]) because raw ADC counts (x ~ 1e6..1e7) make the monomial columns differ by
// up to 1e20 and the design ill-conditioned. The result is re-expanded in raw inputs:
//   u^i v^j = sum_{k<=i} sum_{l<=j} C(i,k) (-c_x)^(i-k) s_x^-i C(j,l) (-c_y)^(j-l) s_y^-j x^k y^l,
// a linear map b = T a of the coefficients, so the raw covariance is T Cov_a T' (exact, no
// linearisation). The map needs every lower monomial x^k y^l of a term in the basis, which holds
// for the complete-degree and tensor bases used here (1-D polynomials, the reference's 10-term
// cubic, the (3, q) surfaces of the improved ADS strategy).
// Not modelled: orthogonal-polynomial bases (monomials on [-1, 1] are well enough conditioned to
// degree 3).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

namespace adahrs::calib {

/// Affine normalisation u = (v - centre) / half_span of one input.
struct InputScaling {
  double centre = 0.0;
  double half_span = 1.0;

  double Normalise(double value) const { return (value - centre) / half_span; }
  /// Maps [min, max] onto [-1, 1]. A zero span keeps half_span = 1, so the design check (not a
  /// division by zero) reports the input that does not vary.
  static InputScaling FromRange(double min, double max);
};

struct Monomial {
  int x_power = 0;
  int y_power = 0;
};

class PolynomialBasis {
 public:
  /// `terms` in coefficient order; names for messages ("x", "y" replaced by the given names).
  PolynomialBasis(std::vector<Monomial> terms, std::string x_name, std::string y_name);

  /// 1, x, ..., x^degree.
  static PolynomialBasis Univariate(int degree, std::string x_name);
  /// The reference's 10-term cubic (thesis section 4.3.1) in its letter order a..j:
  /// 1, x, y, x^2, y^2, x y, x^3, y^3, x y^2, x^2 y.
  static PolynomialBasis ReferenceCubicSurface(std::string x_name, std::string y_name);
  /// Every x^p y^q with p <= x_degree, q <= y_degree, ordered by p then q.
  static PolynomialBasis TensorSurface(int x_degree,
                                       int y_degree,
                                       std::string x_name,
                                       std::string y_name);
  /// The largest power of x and of y among the terms.
  int MaxXPower() const;
  int MaxYPower() const;

  int size() const { return static_cast<int>(terms_.size()); }
  const std::vector<Monomial>& terms() const { return terms_; }
  /// "1", "t", "t^2", "ps x pt^2", ...
  std::vector<std::string> TermNames() const;

  /// The monomials at (x, y), in coefficient order.
  Eigen::RowVectorXd Row(double x, double y = 0.0) const;
  double Evaluate(const Eigen::VectorXd& coefficients, double x, double y = 0.0) const;

  /// T such that raw = T * normalised coefficients (see the header comment). Throws
  /// std::invalid_argument if a term's lower monomial is missing from the basis.
  Eigen::MatrixXd NormalisedToRaw(const InputScaling& x_scaling,
                                  const InputScaling& y_scaling = {}) const;

 private:
  std::vector<Monomial> terms_;
  std::string x_name_;
  std::string y_name_;
};

}  // namespace adahrs::calib
