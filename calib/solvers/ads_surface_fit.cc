#include "calib/solvers/ads_surface_fit.h"

#include <cmath>
#include <set>

#include <fmt/format.h>

namespace adahrs::calib {

SurfaceEstimate FitReferenceSurface(const std::string& context,
                                    const std::vector<SurfaceSample>& samples,
                                    const LeastSquaresOptions& options) {
  constexpr int kMinTemperatures = 4;
  std::set<long long> temperatures_dc;  // chamber temperatures to 0.1 degC
  for (const SurfaceSample& s : samples) temperatures_dc.insert(std::llround(10.0 * s.chamber_c));
  if (static_cast<int>(temperatures_dc.size()) < kMinTemperatures) {
    throw DegenerateDesignError(fmt::format(
        "{}: design refused: {} chamber temperature(s), the cubic's y, y^2, y^3 terms need at "
        "least {} (too few temperatures)",
        context, temperatures_dc.size(), kMinTemperatures));
  }
  std::set<double> references;
  for (const SurfaceSample& s : samples) references.insert(s.z);
  if (static_cast<int>(references.size()) < kMinTemperatures) {
    throw DegenerateDesignError(fmt::format(
        "{}: design refused: {} distinct reference value(s), the cubic's x, x^2, x^3 terms need "
        "at least 4 (too few altitudes or airspeeds)",
        context, references.size()));
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
  const PolynomialBasis basis = PolynomialBasis::ReferenceCubicSurface("x", "y");
  SurfaceEstimate out;
  out.fit = FitPolynomial(context, basis, obs, WeightKind::kInverseVariance,
                          ErrorScale::kResidualVariance, options);
  for (int i = 0; i < 10; ++i) {
    out.surface.coeff[i] = out.fit.raw_coefficients[i];
    out.coeff_se[i] = out.fit.raw_standard_errors[i];
  }
  out.surface.x_min_code = out.fit.x_min;
  out.surface.x_max_code = out.fit.x_max;
  out.surface.y_min_code = out.fit.y_min;
  out.surface.y_max_code = out.fit.y_max;
  out.residual_rms = out.fit.fit.residual_rms;
  out.max_abs_residual = out.fit.fit.max_abs_residual;
  return out;
}

}  // namespace adahrs::calib
