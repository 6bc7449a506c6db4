// The reference ADS calibration strategy (reference-method.md step 6, thesis section 2.9 and
// Table 25), exactly as the reference does it: altitude (ft) as the 10-term bivariate cubic of the
// static code and the static bridge-voltage (temperature) code; airspeed (kt) likewise from the
// pitot code and the pitot bridge-voltage code; equal weights; fitted in normalised inputs
// (calib/solvers/ads_surface_fit.h). Altitude uses every calibration point, airspeed the airspeed
// points (ads_calibration_points.h).
// Output: the constants (firmware_model::AdsCalibrationConstants), their 1-sigma standard errors in
// the same JSON shape as the constants (null where not estimated: the code box), and diagnostics
// (points used, residual RMS and worst residual per output, in ft and kt).
// Not modelled: hysteresis (a single-valued surface cannot hold it), tolerance weighting.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/ads_calibration/ads_calibration_points.h"
#include "calib/constants/ads_fit_diagnostics.h"
#include "calib/solvers/ads_surface_fit.h"
#include "firmware_model/calibration_constants.h"

namespace adahrs::calib {

inline constexpr const char* kReferenceAdsStrategyName = "reference";

struct AdsFitResult {
  std::string strategy;
  firmware_model::AdsCalibrationConstants constants;
  nlohmann::json standard_errors;  ///< shape of firmware_model::ToJson(constants)
  AdsFitDiagnostics diagnostics;
};

/// Fits the reference strategy to `points`; `context` (e.g. the unit serial) leads every message.
/// Throws DegenerateDesignError with the reason for a design the cubic cannot be fitted to.
AdsFitResult FitReferenceAdsStrategy(const std::string& context,
                                     const std::vector<AdsCalibrationPoint>& points);

/// The surfaces' samples of `points`: every point for altitude (static code, static bridge code,
/// ft), the airspeed points for airspeed (pitot code, pitot bridge code, kt); weights 1.
struct AdsSurfaceSamples {
  std::vector<SurfaceSample> altitude;
  std::vector<SurfaceSample> airspeed;
};
AdsSurfaceSamples SurfaceSamplesOf(const std::vector<AdsCalibrationPoint>& points);

/// The result of any 10-term cubic strategy from its two fitted surfaces: constants, standard
/// errors (null for the code box) and diagnostics, labelled `strategy`. With `pressure_laws` the
/// surfaces are of static and impact pressure (Pa) and the firmware's ISA and CAS laws follow.
AdsFitResult AdsFitFromSurfaces(const std::string& strategy,
                                const SurfaceEstimate& altitude,
                                const SurfaceEstimate& airspeed,
                                bool pressure_laws = false);

}  // namespace adahrs::calib
