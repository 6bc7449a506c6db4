#include "proving/demo/demo_campaign.h"

#include "diagnosis/diagnosis_output.h"

namespace adahrs::proving {
namespace {

// Stage 5: every fit through the firmware compensator against the rig's truth, when there is one.
void EvaluateFits(const DemoCampaignOptions& o,
                  calib::CampaignObserver& observer,
                  const calib::CampaignArtifacts& f,
                  calib::CampaignResult& production,
                  DemoCampaignResult& result) {
  if (!o.truth_dir) {
    production.not_run.push_back(
        "evaluation against truth: no truth directory (not a simulated rig)");
    return;
  }
  observer.Stage(
      "5/8 evaluation against the rig's truth: every fit through the firmware "
      "compensator on the envelope grid");
  const double imu_g = f.imu_local_gravity_mps2;
  const double ads_g = f.ads_local_gravity_mps2;
  result.reference_evaluation =
      EvaluateAgainstTruth(f.imu_reference, *o.truth_dir, imu_g, f.imu_reference_dir);
  const std::vector<EvaluatedQuantity> imu =
      EvaluateAgainstTruth(f.imu_joint, *o.truth_dir, imu_g, f.imu_joint_dir);
  result.ads_reference_evaluation =
      EvaluateAgainstTruth(f.ads_reference, *o.truth_dir, ads_g, f.ads_reference_dir);
  const std::vector<EvaluatedQuantity> ads =
      EvaluateAgainstTruth(f.ads_improved, *o.truth_dir, ads_g, f.ads_improved_dir);
  for (const auto* quantities : {&imu, &ads}) {
    for (const EvaluatedQuantity& q : *quantities) result.evaluation[q.serial].push_back(q);
  }
}

// Stage 6: the calibration runs diagnosed against the nominal model, beside the truth and checked
// by replaying the acceptance runs when the rig's truth and a replay function are given.
void DiagnoseCalibrationRuns(const DemoCampaignOptions& o,
                             calib::CampaignObserver& observer,
                             const calib::CampaignArtifacts& f,
                             calib::CampaignResult& production,
                             DemoCampaignResult& result) {
  const std::filesystem::path out_dir = o.campaign.out_dir;
  observer.Stage(
      "6/8 diagnosis: the IMU and ADS calibration runs against the pipeline's nominal model "
      "(adahrs diagnose) -> " +
      (out_dir / "diagnosis").string());
  result.diagnosis_dir = out_dir / "diagnosis";
  std::vector<std::filesystem::path> diagnosed_runs = f.imu_calibration_runs;
  diagnosed_runs.push_back(f.ads_calibration_run);
  const diagnosis::DiagnosisRun diagnosed = diagnosis::DiagnoseRuns(diagnosed_runs, std::nullopt);
  diagnosis::WriteDiagnosis(diagnosed, result.diagnosis_dir);
  result.diagnosis = diagnosed.units;
  if (o.truth_dir)
    result.diagnosis_truth = CompareDiagnosisWithTruth(diagnosed.units, *o.truth_dir);
  if (o.truth_dir && o.replay) {
    result.replay_checks = CheckDiagnosisByReplay(diagnosed,
                                                  *o.truth_dir,
                                                  result.diagnosis_dir,
                                                  {f.imu_acceptance_run, f.ads_acceptance_run},
                                                  o.replay);
  } else {
    production.not_run.push_back(
        "re-simulation check of the diagnosis: needs the rig's truth and a replay function");
  }
}

}  // namespace

DemoCampaignResult RunDemoCampaign(const DemoCampaignOptions& options,
                                   calib::CampaignObserver& observer,
                                   const std::atomic<bool>& stop) {
  DemoCampaignResult result;
  calib::CampaignOptions campaign = options.campaign;
  campaign.before_reports = [&](const calib::CampaignArtifacts& artifacts,
                                calib::CampaignResult& production) {
    EvaluateFits(options, observer, artifacts, production, result);
    DiagnoseCalibrationRuns(options, observer, artifacts, production, result);
  };
  result.production = calib::RunCampaign(campaign, observer, stop);
  return result;
}

}  // namespace adahrs::proving
