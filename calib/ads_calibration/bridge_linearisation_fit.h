// The bridge-voltage code's linearisation in die temperature (firmware_model's
// BridgeLinearisation, target/bridge_linearisation.h), estimated from the calibration points: the
// bridge code y as a quadratic of the chamber temperature, y = a + b t + c t^2 (t the chamber
// temperature less the points' mean), gives origin = a rounded to a whole code and curvature
// kappa = 4 c / b^2, which make s(y) = origin + b t exactly for the fitted quadratic.
// Units: codes in counts, t in degC, residual in degC.
// Derivation, standard error of kappa, refusals (DegenerateDesignError):
// docs/calibration-strategies.md ("The bridge code's linearisation").
// Left out: self-heating (an offset t need not know); the current source's tempco and the bridge
// resistance's pressure dependence stay in the residual.
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
