#include "calib/solvers/ads_surface_fit.h"

namespace adahrs::calib {

SurfaceEstimate FitReferenceSurface(const std::string& context,
                                    const std::vector<SurfaceSample>& samples,
                                    const LeastSquaresOptions& options) {
  PolynomialObservations obs;
  for (const SurfaceSample& s : samples) {
    obs.x.push_back(s.x_code);
    obs.y.push_back(s.y_code);
    obs.z.push_back(s.z);
  }
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
