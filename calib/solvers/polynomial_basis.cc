#include "calib/solvers/polynomial_basis.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

namespace adahrs::calib {
namespace {

// std::pow(v, p) for a whole power, with the powers 0 and 1 (whose results pow returns exactly:
// 1 and v) taken without the call. Design matrices of a million rows call this per cell.
double WholePower(double v, int p) {
  if (p == 0) return 1.0;
  if (p == 1) return v;
  return std::pow(v, p);
}

double Binomial(int n, int k) {
  double out = 1.0;
  for (int i = 1; i <= k; ++i) out = out * (n - k + i) / i;
  return out;
}

std::string PowerName(const std::string& name, int power) {
  if (power == 0) return "";
  return power == 1 ? name : fmt::format("{}^{}", name, power);
}

}  // namespace

InputScaling InputScaling::FromRange(double min, double max) {
  const double half_span = 0.5 * (max - min);
  return InputScaling{0.5 * (min + max), half_span > 0.0 ? half_span : 1.0};
}

PolynomialBasis::PolynomialBasis(std::vector<Monomial> terms,
                                 std::string x_name,
                                 std::string y_name)
    : terms_(std::move(terms)), x_name_(std::move(x_name)), y_name_(std::move(y_name)) {}

PolynomialBasis PolynomialBasis::Univariate(int degree, std::string x_name) {
  std::vector<Monomial> terms;
  for (int i = 0; i <= degree; ++i) terms.push_back({i, 0});
  return PolynomialBasis(std::move(terms), std::move(x_name), "y");
}

PolynomialBasis PolynomialBasis::ReferenceCubicSurface(std::string x_name, std::string y_name) {
  return PolynomialBasis(
      {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {0, 2}, {1, 1}, {3, 0}, {0, 3}, {1, 2}, {2, 1}},
      std::move(x_name),
      std::move(y_name));
}

PolynomialBasis PolynomialBasis::TensorSurface(int x_degree,
                                               int y_degree,
                                               std::string x_name,
                                               std::string y_name) {
  std::vector<Monomial> terms;
  for (int p = 0; p <= x_degree; ++p) {
    for (int q = 0; q <= y_degree; ++q) terms.push_back({p, q});
  }
  return PolynomialBasis(std::move(terms), std::move(x_name), std::move(y_name));
}

int PolynomialBasis::MaxXPower() const {
  int m = 0;
  for (const Monomial& t : terms_) m = std::max(m, t.x_power);
  return m;
}

int PolynomialBasis::MaxYPower() const {
  int m = 0;
  for (const Monomial& t : terms_) m = std::max(m, t.y_power);
  return m;
}

std::vector<std::string> PolynomialBasis::TermNames() const {
  std::vector<std::string> names;
  for (const Monomial& m : terms_) {
    const std::string x = PowerName(x_name_, m.x_power);
    const std::string y = PowerName(y_name_, m.y_power);
    if (x.empty() && y.empty()) {
      names.push_back("1");
    } else {
      names.push_back(x.empty() ? y : (y.empty() ? x : x + " " + y));
    }
  }
  return names;
}

Eigen::RowVectorXd PolynomialBasis::Row(double x, double y) const {
  Eigen::RowVectorXd row(size());
  for (int k = 0; k < size(); ++k) {
    row[k] = WholePower(x, terms_[k].x_power) * WholePower(y, terms_[k].y_power);
  }
  return row;
}

double PolynomialBasis::Evaluate(const Eigen::VectorXd& coefficients, double x, double y) const {
  return Row(x, y).dot(coefficients);
}

Eigen::MatrixXd PolynomialBasis::NormalisedToRaw(const InputScaling& sx,
                                                 const InputScaling& sy) const {
  auto index_of = [&](int i, int j) {
    for (int k = 0; k < size(); ++k) {
      if (terms_[k].x_power == i && terms_[k].y_power == j) return k;
    }
    throw std::invalid_argument(fmt::format(
        "polynomial basis: monomial {}^{} {}^{} needed for the raw re-expansion is missing",
        x_name_,
        i,
        y_name_,
        j));
  };
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(size(), size());
  for (int col = 0; col < size(); ++col) {
    const int i = terms_[col].x_power;
    const int j = terms_[col].y_power;
    for (int k = 0; k <= i; ++k) {
      for (int l = 0; l <= j; ++l) {
        t(index_of(k, l), col) += Binomial(i, k) * std::pow(-sx.centre, i - k) * Binomial(j, l) *
                                  std::pow(-sy.centre, j - l) /
                                  (std::pow(sx.half_span, i) * std::pow(sy.half_span, j));
      }
    }
  }
  return t;
}

}  // namespace adahrs::calib
