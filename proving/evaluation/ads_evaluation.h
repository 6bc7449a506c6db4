// Evaluation of ADS calibration constants against a simulated unit's TRUE model
// (`adahrs evaluate`): the constants go through the exporter and the fixed-point firmware
// compensator (firmware_model/target/ads_compensator.h), fed with the codes the unit's true model
// (sensor_sim::AdsUnitParams from truth/<serial>.json) produces on a dense grid, noise off; the
// outputs are compared with the true altitude (ISA of the applied static pressure) and calibrated
// airspeed (of the applied impact pressure).
//
// Grid: altitude -1,000...50,000 ft (at zero airspeed) and airspeed 30...450 kt (at sea level),
// each x -40...+85 degC, in the steps of AdsEvaluationOptions; the die at its steady state in the
// chamber air (self-heating included; the thermal lag is not exercised: every point is a soak).
//
// History. The bridges' pressure and thermal hysteresis depend on the pressure and temperature
// extremes not yet wiped out (sensor_sim/preisach_hysteresis.h), which no static calibration sees.
// The evaluation never switches them off; it evaluates every grid point under each history of the
// major loops of the operating envelope:
//   pressure: "none" (operator fresh, the loop centre), "rising" (after the opposite end of the
//     envelope: static 50,000 -> -1,000 ft then climbing; pitot 450 -> 30 kt then accelerating is
//     written "rising" for the impact pressure), "falling" (the reverse);
//   temperature: "none", "heating" (85 -> -40 degC then heating), "cooling" (-40 -> 85 then
//   cooling).
// The firmware sees the whole history too: its hysteresis operators (ads_compensator.h) start
// fresh with the unit and compensate every frame of it, as in a unit powered through the history.
// Per grid point: the error without history (both operators fresh), the worst |error| over the
// nine histories, and the loop half-width (max - min)/2 of the error over them: a static
// calibration returns one value where the truth spans that band, so no static calibration can
// have a worst error below the half-width. Verdict: pass (worst <= tolerance); for a static
// surface (no hysteresis terms), unreachable where the half-width > tolerance (says so with the
// number); else fail. A surface with hysteresis terms is not static: what its half-width shows
// is what its compensation left, so it has no unreachable points.
// Not modelled: the converter noise (off by design), pneumatic lag, Mach/TAS.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "firmware_model/calibration_constants.h"
#include "sensor_sim/ads_unit.h"

namespace adahrs::proving {

struct AdsEvaluationOptions {
  double alt_step_ft = 1000.0;
  double cas_step_kt = 10.0;
  double temp_step_c = 5.0;
};

enum class AdsVerdict { kPass, kFail, kUnreachable };
const char* ToString(AdsVerdict verdict);

struct AdsGridPoint {
  double value = 0.0;               ///< true altitude ft or airspeed kt
  double temp_c = 0.0;              ///< chamber air
  double tolerance = 0.0;           ///< +- ft or kt
  double error_no_history = 0.0;    ///< compensated - true, operators fresh
  double worst_with_history = 0.0;  ///< max |error| over the nine histories
  double loop_half_width = 0.0;     ///< (max - min)/2 of the error over the histories
  AdsVerdict verdict = AdsVerdict::kPass;
};

/// Worst case over temperature at one tolerance-table point.
struct AdsTolerancePointResult {
  double at = 0.0;
  double tolerance = 0.0;
  double worst_no_history = 0.0;  ///< max |error_no_history| over temperature
  double worst_no_history_temp_c = 0.0;
  double worst_with_history = 0.0;
  double max_loop_half_width = 0.0;
  AdsVerdict verdict = AdsVerdict::kPass;  ///< worst verdict over temperature
};

struct AdsQuantityEvaluation {
  std::string quantity;  ///< "altitude_ft" or "airspeed_kt"
  std::vector<AdsGridPoint> grid;
  std::vector<AdsTolerancePointResult> points;
  int saturated_frames = 0;  ///< compensator frames with a saturation flag
  /// Largest |error_no_history| / tolerance over the grid (<= 1: the calibration itself passes).
  double worst_ratio_no_history = 0.0;
  int pass = 0, fail = 0, unreachable = 0;  ///< grid points by verdict
};

struct AdsEvaluation {
  AdsQuantityEvaluation altitude;
  AdsQuantityEvaluation airspeed;
  nlohmann::json ToJson() const;
};

/// Evaluates `constants` on the unit `truth`; throws std::invalid_argument (from the exporter)
/// if the constants cannot be represented in the firmware.
AdsEvaluation EvaluateAdsConstants(const firmware_model::AdsCalibrationConstants& constants,
                                   const sensor_sim::AdsUnitParams& truth,
                                   const AdsEvaluationOptions& options = {});

}  // namespace adahrs::proving
