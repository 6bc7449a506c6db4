// The evaluation of one ADS constants file against its simulated unit's true model, as
// `adahrs evaluate` and the demo's truth stage write it (evaluation.json, format
// "adahrs-ads-evaluation", docs/evaluation-format.md): EvaluateAdsConstants (ads_evaluation.h) on
// its grid, each quantity's verdict in words, and the document with every grid point.
// Units: altitude in ft, airspeed in kt, temperature in degC; "worst_ratio_no_history" is
// |compensated - true| / tolerance (1 = at the tolerance).
// Left out: what EvaluateAdsConstants leaves out (converter noise, pneumatic lag, Mach/TAS).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "calib/constants/constants_file.h"
#include "proving/evaluation/ads_evaluation.h"
#include "sensor_sim/ads_unit.h"

namespace adahrs::proving {

struct AdsFileEvaluation {
  AdsEvaluation evaluation;
  std::string altitude_verdict;
  std::string airspeed_verdict;
  nlohmann::json report;  ///< evaluation.json
};

/// A quantity's verdict over its grid: "within specification", or how many grid points fail and
/// how many no static calibration can reach.
std::string AdsVerdictText(const AdsQuantityEvaluation& q);

/// Evaluates `constants` (kind ads) against `truth`; throws std::invalid_argument when they are
/// not an ADS's, or with the exporter's reason when the firmware cannot hold them.
AdsFileEvaluation EvaluateAds(const calib::ConstantsFile& constants,
                              const sensor_sim::AdsUnitParams& truth,
                              const AdsEvaluationOptions& options = {});

}  // namespace adahrs::proving
