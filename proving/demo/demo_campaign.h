// The demo's campaign: the production campaign (calib/campaign/campaign.h) with the truth stages
// injected before its reports (docs/demo.md):
//   5. evaluation against the simulator's truth when `truth_dir` is given (truth_evaluation.h),
//      for every fit                                           -> fits/<…>/evaluation.json
//   6. diagnosis of the IMU and ADS calibration runs against the pipeline's nominal model
//      (diagnosis/), beside the truth when `truth_dir` is given (diagnosis_truth.h)
//                                                -> diagnosis/diagnosis.json, report.html
//      and, with a truth directory and a replay function, the held-out check: each unit's truth
//      without the vocabulary's effects (the base) and it with the findings (model.json), the
//      acceptance runs re-simulated with either and compared with their recordings
//                          -> diagnosis/models/<serial>/{base,model}.json,
//                          diagnosis/replay_check.{json,html}
// Stages that cannot run (no truth on a real rig) are listed in `not_run` with the reason.
#pragma once

#include <atomic>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "calib/campaign/campaign.h"
#include "diagnosis/imu_diagnosis.h"
#include "diagnosis/replay_comparison.h"
#include "proving/demo/diagnosis_truth.h"
#include "proving/demo/truth_evaluation.h"

namespace adahrs::proving {

struct DemoCampaignOptions {
  calib::CampaignOptions campaign;                 ///< its before_reports is set by RunDemoCampaign
  std::optional<std::filesystem::path> truth_dir;  ///< simulated rigs only
  /// Re-simulates a run with unit files (the application's rig_sim::ReplayRecording); empty: the
  /// held-out re-simulation check is not run.
  diagnosis::ReplayFunction replay;
};

struct DemoCampaignResult {
  calib::CampaignResult production;
  /// Each downloaded unit's evaluation against its truth, by serial (empty: no truth).
  std::map<std::string, std::vector<EvaluatedQuantity>> evaluation;
  std::vector<EvaluatedQuantity> reference_evaluation;      ///< IMU reference strategy
  std::vector<EvaluatedQuantity> ads_reference_evaluation;  ///< ADS reference strategy
  /// The calibration runs diagnosed against the pipeline's nominal model (diagnosis/).
  std::vector<diagnosis::UnitDiagnosis> diagnosis;
  std::vector<DiagnosisTruthLine> diagnosis_truth;  ///< empty without a truth directory
  /// The acceptance runs re-simulated with the base and the augmented models (empty without a
  /// truth directory or a replay function).
  std::vector<diagnosis::ReplayComparison> replay_checks;
  std::filesystem::path diagnosis_dir;
};

DemoCampaignResult RunDemoCampaign(const DemoCampaignOptions& options,
                                   calib::CampaignObserver& observer,
                                   const std::atomic<bool>& stop);

}  // namespace adahrs::proving
