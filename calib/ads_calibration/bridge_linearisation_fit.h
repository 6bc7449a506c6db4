// The bridge-voltage code's linearisation in die temperature (firmware_model's
// BridgeLinearisation, target/bridge_linearisation.h), estimated from the calibration points.
//
// Model: at each soak the bridge code y is a quadratic of the chamber temperature T,
//   y = a + b t + c t^2,   t = T - (mean chamber temperature of the points),
// fitted by the project's least-squares driver (calib/solvers/polynomial_fit.h; every point
// weighs the same). The linearisation's origin is a, rounded to a whole code, and its curvature
// kappa = 4 c / b^2, which makes s(y) = origin + b t exactly for the fitted quadratic. The die's
// self-heating is an offset between die and chamber that t does not need to know; what the fit
// leaves (the current source's tempco, a cubic; the bridge resistance's pressure dependence, a
// scatter across the points of one soak) stays in the residual, reported in degC.
// Standard error of kappa: first order through (b, c), from the fit's residual-variance
// covariance (the residual is partly systematic, so it is an indication rather than a bound).
// Refused (DegenerateDesignError, naming the context): fewer than 3 chamber temperatures, a
// design the driver refuses, a slope of less than one code over the temperatures' travel, or a
// curvature that turns the quadratic inside the points' code range (1 + kappa (y - origin) <= 0
// at some point).
#pragma once

#include <string>
#include <vector>

#include "calib/solvers/ads_surface_fit.h"
#include "firmware_model/calibration_constants.h"

namespace adahrs::calib {

struct BridgeLinearisationFit {
  firmware_model::BridgeLinearisation linearisation;
  double curvature_se_per_code = 0.0;  ///< standard error of kappa
  double slope_cnt_per_c = 0.0;        ///< b: the linearised code's change per degC
  double residual_rms_c = 0.0;         ///< rms of (y - quadratic) / b
};

/// Fits the linearisation of the samples' y codes (their chamber temperatures as T).
BridgeLinearisationFit FitBridgeLinearisation(const std::string& context,
                                              const std::vector<SurfaceSample>& samples);

/// The samples with each y code replaced by its linearised code.
std::vector<SurfaceSample> Linearised(std::vector<SurfaceSample> samples,
                                      const firmware_model::BridgeLinearisation& linearisation);

}  // namespace adahrs::calib
