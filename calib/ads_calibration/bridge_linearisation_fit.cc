#include "calib/ads_calibration/bridge_linearisation_fit.h"

#include <cmath>
#include <set>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "calib/solvers/linear_least_squares.h"
#include "firmware_model/reference_compensator.h"

namespace adahrs::calib {

BridgeLinearisationFit FitBridgeLinearisation(const std::string& context,
                                              const std::vector<SurfaceSample>& samples) {
  const std::set<long long> temperatures_dc = ChamberTemperaturesDc(samples);
  if (temperatures_dc.size() < 3) {
    throw DegenerateDesignError(fmt::format(
        "{}: the bridge code's quadratic in temperature needs 3 chamber temperatures, got {}",
        context, temperatures_dc.size()));
  }
  double mean_c = 0.0;
  for (const SurfaceSample& s : samples) mean_c += s.chamber_c;
  mean_c /= static_cast<double>(samples.size());
  const auto n = static_cast<Eigen::Index>(samples.size());
  Eigen::MatrixXd a(n, 3);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = samples[static_cast<size_t>(i)].chamber_c - mean_c;
    a.row(i) << 1.0, t, t * t;
    y(i) = samples[static_cast<size_t>(i)].y_code;
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  const Eigen::Vector3d c = qr.solve(y);
  const double slope = c(1), curve = c(2);
  const double travel_c = (*temperatures_dc.rbegin() - *temperatures_dc.begin()) / 10.0;
  if (!(std::abs(slope) * travel_c >= 1.0) || !std::isfinite(curve)) {
    throw DegenerateDesignError(fmt::format(
        "{}: the bridge code changes by less than a code over {:.1f} degC of chamber temperature",
        context, travel_c));
  }
  BridgeLinearisationFit out;
  out.linearisation.origin_code = std::nearbyint(c(0));
  out.linearisation.curvature_per_code = 4.0 * curve / (slope * slope);
  out.slope_code_per_degc = slope;
  const double residual_ss = (a * c - y).squaredNorm();
  out.residual_rms_c = std::sqrt(residual_ss / static_cast<double>(n)) / std::abs(slope);
  const double variance = n > 3 ? residual_ss / static_cast<double>(n - 3) : 0.0;
  const Eigen::Matrix3d ata_inv = (a.transpose() * a).inverse();
  const Eigen::Vector2d gradient(-8.0 * curve / (slope * slope * slope), 4.0 / (slope * slope));
  const Eigen::Matrix2d covariance = variance * ata_inv.bottomRightCorner<2, 2>();
  out.curvature_se_per_code = std::sqrt(gradient.dot(covariance * gradient));
  for (const SurfaceSample& s : samples) {
    if (!(1.0 + out.linearisation.curvature_per_code * (s.y_code - out.linearisation.origin_code) > 0.0)) {
      throw DegenerateDesignError(fmt::format(
          "{}: the bridge code's fitted quadratic in temperature turns inside the calibrated range "
          "(at code {:.0f}, {:.1f} degC)", context, s.y_code, s.chamber_c));
    }
  }
  return out;
}

std::vector<SurfaceSample> Linearised(std::vector<SurfaceSample> samples,
                                      const firmware_model::BridgeLinearisation& linearisation) {
  for (SurfaceSample& s : samples) s.y_code = firmware_model::LinearisedBridgeCode(linearisation, s.y_code);
  return samples;
}

}  // namespace adahrs::calib
