#include "calib/ads_calibration/bridge_linearisation_fit.h"

#include <cmath>
#include <set>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "calib/solvers/polynomial_fit.h"
#include "firmware_model/reference_compensator.h"

namespace adahrs::calib {

BridgeLinearisationFit FitBridgeLinearisation(const std::string& context,
                                              const std::vector<SurfaceSample>& samples) {
  const std::set<long long> temperatures_dc = ChamberTemperaturesDc(samples);
  if (temperatures_dc.size() < 3) {
    throw DegenerateDesignError(fmt::format(
        "{}: the bridge code's quadratic in temperature needs 3 chamber temperatures, got {}",
        context,
        temperatures_dc.size()));
  }
  double mean_c = 0.0;
  for (const SurfaceSample& s : samples) mean_c += s.chamber_c;
  mean_c /= static_cast<double>(samples.size());
  PolynomialObservations obs;
  for (const SurfaceSample& s : samples) {
    obs.x.push_back(s.chamber_c - mean_c);
    obs.z.push_back(s.y_code);
  }
  const PolynomialFit fit = FitPolynomial(context + ": bridge code against chamber temperature",
                                          PolynomialBasis::Univariate(2, "t"),
                                          obs,
                                          WeightKind::kInverseVariance,
                                          ErrorScale::kResidualVariance);
  const Eigen::VectorXd& c = fit.raw_coefficients;  // y = c0 + c1 t + c2 t^2
  const double slope = c(1), curve = c(2);
  const double travel_c = (*temperatures_dc.rbegin() - *temperatures_dc.begin()) / 10.0;
  if (!(std::abs(slope) * travel_c >= 1.0)) {
    throw DegenerateDesignError(fmt::format(
        "{}: the bridge code changes by less than a code over {:.1f} degC of chamber temperature",
        context,
        travel_c));
  }
  BridgeLinearisationFit out;
  out.linearisation.origin_code = std::nearbyint(c(0));
  out.linearisation.curvature_per_code = 4.0 * curve / (slope * slope);
  out.slope_cnt_per_c = slope;
  out.residual_rms_c = fit.fit.residual_rms / std::abs(slope);
  const Eigen::Vector2d gradient(-8.0 * curve / (slope * slope * slope), 4.0 / (slope * slope));
  const Eigen::Matrix2d covariance = fit.raw_covariance.bottomRightCorner<2, 2>();
  out.curvature_se_per_code = std::sqrt(gradient.dot(covariance * gradient));
  const firmware_model::BridgeLinearisation& l = out.linearisation;
  for (const SurfaceSample& s : samples) {
    if (!(1.0 + l.curvature_per_code * (s.y_code - l.origin_code) > 0.0)) {
      throw DegenerateDesignError(fmt::format(
          "{}: the bridge code's fitted quadratic in temperature turns inside the calibrated "
          "range (at code {:.0f}, {:.1f} degC)",
          context,
          s.y_code,
          s.chamber_c));
    }
  }
  return out;
}

std::vector<SurfaceSample> Linearised(std::vector<SurfaceSample> samples,
                                      const firmware_model::BridgeLinearisation& linearisation) {
  for (SurfaceSample& s : samples) {
    s.y_code = firmware_model::LinearisedBridgeCode(linearisation, s.y_code);
  }
  return samples;
}

}  // namespace adahrs::calib
