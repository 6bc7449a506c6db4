// The truth-evaluation stage of a campaign on a simulated rig: each unit's constants
// (constants.json) are evaluated against the unit's true model, which the rig wrote to
// `<truth_dir>/<serial>.json` ({"serial", "kind", "seed", "model_profile", "params"}): IMUs with
// EvaluateImu (imu_evaluation.h), ADS units with EvaluateAds (ads_evaluation_report.h). Only a
// caller that made the rig knows where its truth is; no pipeline stage reads it.
// Writes `<fit_dir>/evaluation.json` ({"units": [one row per unit and quantity]}, the table the
// report shows) and each unit's full evaluation to `<fit_dir>/evaluation/<serial>.json`.
// Errors: a missing or malformed truth file throws common::ParamError naming it and the JSON
// path; constants the exporter refuses throw std::invalid_argument with its reason.
// Left out: units without a constants file in `constants` (not evaluated).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "calib/campaign/campaign_fits.h"

namespace adahrs::proving {

/// One evaluated quantity of one unit.
struct EvaluatedQuantity {
  std::string serial;
  std::string quantity;  ///< "acceleration", "body rate", "altitude", "airspeed"
  std::string unit;      ///< of worst and tolerance: "mg", "deg/s", "x tolerance"
  double worst = 0.0;    ///< worst error over the envelope grid
  double tolerance = 0.0;
  std::string verdict;
};

/// Evaluates every file of `constants` and writes the evaluation files into `fit_dir`.
std::vector<EvaluatedQuantity> EvaluateAgainstTruth(
    const std::vector<calib::WrittenConstants>& constants,
    const std::filesystem::path& truth_dir,
    double g_local_mps2,
    const std::filesystem::path& fit_dir);

}  // namespace adahrs::proving
