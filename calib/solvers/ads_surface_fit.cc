#include "calib/solvers/ads_surface_fit.h"

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

namespace adahrs::calib {

std::set<long long> ChamberTemperaturesDc(const std::vector<SurfaceSample>& samples) {
  std::set<long long> temperatures_dc;
  for (const SurfaceSample& s : samples)
    temperatures_dc.insert(ChamberTemperatureKeyDc(s.chamber_c));
  return temperatures_dc;
}

SurfaceEstimate FitSurface(const std::string& context,
                           const PolynomialBasis& basis,
                           const std::vector<SurfaceSample>& samples,
                           HistoryTerms history,
                           const LeastSquaresOptions& options) {
  namespace fm = firmware_model;
  if (basis.MaxXPower() > fm::kSurfaceXDegree || basis.MaxYPower() > fm::kSurfaceYDegree) {
    throw std::invalid_argument(
        fmt::format("{}: a surface of degree ({}, {}) exceeds the firmware's ({}, {})",
                    context,
                    basis.MaxXPower(),
                    basis.MaxYPower(),
                    fm::kSurfaceXDegree,
                    fm::kSurfaceYDegree));
  }
  const int min_temperatures = basis.MaxYPower() + 1;
  const std::set<long long> temperatures_dc = ChamberTemperaturesDc(samples);
  if (static_cast<int>(temperatures_dc.size()) < min_temperatures) {
    throw DegenerateDesignError(fmt::format(
        "{}: design refused: {} chamber temperature(s), the surface's terms up to y^{} need at "
        "least {} (too few temperatures)",
        context,
        temperatures_dc.size(),
        basis.MaxYPower(),
        min_temperatures));
  }
  const int min_references = basis.MaxXPower() + 1;
  std::set<double> references;
  for (const SurfaceSample& s : samples) references.insert(s.z);
  if (static_cast<int>(references.size()) < min_references) {
    throw DegenerateDesignError(fmt::format(
        "{}: design refused: {} distinct reference value(s), the surface's terms up to x^{} need "
        "at least {} (too few altitudes or airspeeds)",
        context,
        references.size(),
        basis.MaxXPower(),
        min_references));
  }
  PolynomialObservations obs;
  bool weighted = false;
  for (const SurfaceSample& s : samples) {
    obs.x.push_back(s.x_code);
    obs.y.push_back(s.y_code);
    obs.z.push_back(s.z);
    obs.weights.push_back(s.weight);
    weighted = weighted || s.weight != 1.0;
  }
  if (!weighted) obs.weights.clear();
  // The slopes' columns in units of 100 degC, so that all four are of order 1.
  constexpr double kSlopeUnitC = 100.0;
  if (history != HistoryTerms::kNone) {
    obs.extra_names = {"s_pressure", "s_thermal"};
    obs.extra_columns.resize(2);
    for (const SurfaceSample& s : samples) {
      obs.extra_columns[0].push_back(s.s_pressure);
      obs.extra_columns[1].push_back(s.s_thermal);
    }
  }
  if (history == HistoryTerms::kWithTemperatureSlopes) {
    obs.extra_names.insert(obs.extra_names.end(), {"s_pressure dT", "s_thermal dT"});
    obs.extra_columns.resize(4);
    for (const SurfaceSample& s : samples) {
      const double dt = (s.chamber_c - kHysteresisReferenceC) / kSlopeUnitC;
      obs.extra_columns[2].push_back(s.s_pressure * dt);
      obs.extra_columns[3].push_back(s.s_thermal * dt);
    }
  }
  SurfaceEstimate out;
  for (auto& row : out.coeff_se) row.fill(std::numeric_limits<double>::quiet_NaN());
  out.fit = FitPolynomial(
      context, basis, obs, WeightKind::kInverseVariance, ErrorScale::kResidualVariance, options);
  for (int i = 0; i < basis.size(); ++i) {
    const Monomial& m = basis.terms()[i];
    out.surface.coeff_xy[m.x_power][m.y_power] = out.fit.raw_coefficients[i];
    out.coeff_se[m.x_power][m.y_power] = out.fit.raw_standard_errors[i];
  }
  if (history != HistoryTerms::kNone) {
    const Eigen::Index k = basis.size();
    const Eigen::VectorXd& c = out.fit.raw_coefficients;
    const Eigen::VectorXd& se = out.fit.raw_standard_errors;
    HysteresisEstimate h{c[k], se[k], c[k + 1], se[k + 1]};
    if (history == HistoryTerms::kWithTemperatureSlopes) {
      h.pressure_per_c = c[k + 2] / kSlopeUnitC;
      h.pressure_per_c_se = se[k + 2] / kSlopeUnitC;
      h.thermal_per_c = c[k + 3] / kSlopeUnitC;
      h.thermal_per_c_se = se[k + 3] / kSlopeUnitC;
    }
    out.history = h;
  }
  out.terms = basis.size();
  out.y_degree = basis.MaxYPower();
  out.surface.x_min_code = out.fit.x_min;
  out.surface.x_max_code = out.fit.x_max;
  out.surface.y_min_code = out.fit.y_min;
  out.surface.y_max_code = out.fit.y_max;
  out.residual_rms = out.fit.fit.residual_rms;
  out.max_abs_residual = out.fit.fit.max_abs_residual;
  return out;
}

SurfaceEstimate FitReferenceSurface(const std::string& context,
                                    const std::vector<SurfaceSample>& samples,
                                    const LeastSquaresOptions& options) {
  return FitSurface(context,
                    PolynomialBasis::ReferenceCubicSurface("x", "y"),
                    samples,
                    HistoryTerms::kNone,
                    options);
}

}  // namespace adahrs::calib
