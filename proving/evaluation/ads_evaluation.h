// Evaluation of ADS calibration constants against a simulated unit's TRUE model (`adahrs
// evaluate`): the constants go through the exporter and the fixed-point firmware compensator
// (firmware_model/target/ads_compensator.h), fed with the codes the true model
// (sensor_sim::AdsUnitParams from truth/<serial>.json) produces on a dense grid, noise off, die
// soaked; outputs compared with the true altitude and calibrated airspeed. Every grid point is
// evaluated under nine histories of the envelope's major loops (pressure none/rising/falling x
// temperature none/heating/cooling), the firmware's own hysteresis operators seeing them too:
// error without history, worst error over the histories, loop half-width. Verdict pass, fail, or
// (static surfaces only) unreachable where the half-width exceeds the tolerance.
// Units: altitude in ft, airspeed in kt, temperature in degC, pressures in Pa.
// Grid, histories, verdicts and measured figures: docs/calibration-strategies.md ("Evaluation
// against the truth").
// Left out: the converter noise (off by design), pneumatic lag, Mach/TAS.
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
