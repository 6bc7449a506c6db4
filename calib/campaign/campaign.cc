#include "calib/campaign/campaign.h"

#include <fmt/format.h>

#include "calib/acceptance/acceptance_file.h"
#include "calib/campaign/bench_runs.h"
#include "calib/ads_calibration/tolerance_ads_strategy.h"
#include "calib/campaign/campaign_fits.h"
#include "calib/diagnosis/diagnosis_output.h"
#include "calib/records/acceptance_records.h"
#include "calib/records/records_sources.h"
#include "calib/records/records_store.h"
#include "calib/report/run_report.h"
#include "calib/sequence/sequence_json.h"
#include "hil/station.h"

namespace adahrs::calib {
namespace {

constexpr const char* kImuBench = "IMU bench";
constexpr const char* kAdsBench = "ADS bench";

std::filesystem::path RunDir(const CampaignOptions& o, const std::string& sequence_file) {
  return o.out_dir / "runs" / ParseSequenceFile(sequence_file).sequence.name;
}

std::vector<std::vector<RunSummary>> RunBenches(const CampaignOptions& o, CampaignObserver& observer,
                                                const std::vector<std::string>& imu_sequences,
                                                const std::vector<std::string>& ads_sequences,
                                                const std::atomic<bool>& stop) {
  BenchPlan imu{kImuBench, o.imu_station_file, {}, &observer.Bench(kImuBench)};
  for (const std::string& s : imu_sequences) imu.runs.push_back({s, RunDir(o, s)});
  BenchPlan ads{kAdsBench, o.ads_station_file, {}, &observer.Bench(kAdsBench)};
  for (const std::string& s : ads_sequences) ads.runs.push_back({s, RunDir(o, s)});
  return RunBenchesConcurrently({imu, ads}, o.executor, stop);
}

std::string RunsText(const std::vector<std::vector<RunSummary>>& benches) {
  std::string text;
  for (const auto& bench : benches) {
    for (const RunSummary& s : bench) {
      text += fmt::format("\n  {}: {}, {} rows, {} packets lost", s.run_dir.string(), s.status,
                          s.rows, s.lost);
    }
  }
  return text;
}

// Judges an acceptance run, writes acceptance.json per unit into `run`/acceptance and records
// every point; returns the judgement.
AcceptanceRun JudgeIntoRecords(const std::filesystem::path& run, const std::string& software_version,
                               RecordsStore& records) {
  const Specification spec = Specification::Reference();
  const AcceptanceRun judged = JudgeAcceptance(run, spec);
  for (const std::filesystem::path& file :
       WriteAcceptanceFiles(judged, spec, software_version, run / "acceptance")) {
    const AcceptanceRecords points = AcceptanceRecordsFromFile(file);
    records.AddAcceptance(points.source_sha256, points.points);
  }
  return judged;
}

}  // namespace

CampaignResult RunCampaign(const CampaignOptions& o, CampaignObserver& observer,
                           const std::atomic<bool>& stop) {
  CampaignResult result;
  const CampaignSequences& seq = o.sequences;
  const hil::Station imu_station = hil::Station::Load(o.imu_station_file);
  const hil::Station ads_station = hil::Station::Load(o.ads_station_file);
  result.records_file = o.out_dir / "records.sqlite";
  RecordsStore records(result.records_file);

  observer.Stage("1/8 calibration runs: IMU calibration on the IMU bench, ADS calibration on the "
                 "ADS bench, concurrently");
  const auto calibration = RunBenches(o, observer, seq.imu_calibration, {seq.ads_calibration}, stop);
  observer.Stage("calibration runs done:" + RunsText(calibration));
  for (const auto& bench : calibration) result.runs.insert(result.runs.end(), bench.begin(), bench.end());
  std::vector<std::filesystem::path> imu_runs;
  for (const std::string& s : seq.imu_calibration) imu_runs.push_back(RunDir(o, s));
  const std::filesystem::path ads_run = RunDir(o, seq.ads_calibration);

  observer.Stage("2/8 fits: IMU reference and improved (joint, firmware format 3) strategies, ADS "
                 "reference and improved (hysteresis-compensated pressure surfaces, ISA / CAS "
                 "laws) strategies");
  const std::filesystem::path imu_reference_dir = o.out_dir / "fits" / "imu-reference";
  const std::filesystem::path imu_joint_dir = o.out_dir / "fits" / "imu-joint";
  const std::filesystem::path ads_reference_dir = o.out_dir / "fits" / "ads-reference";
  const std::filesystem::path ads_improved_dir = o.out_dir / "fits" / "ads-hysteresis-compensated";
  const auto imu_reference = FitImuIntoDirectory(imu_runs, ImuStrategy::Reference(),
                                                 imu_reference_dir, o.software_version);
  ImuStrategy improved = ImuStrategy::Improved();
  improved.format3 = true;
  const auto imu_joint = FitImuIntoDirectory(imu_runs, improved, imu_joint_dir, o.software_version);
  const auto ads_reference = FitAdsIntoDirectory(ads_run, kReferenceAdsStrategyName,
                                                 ads_reference_dir, o.software_version);
  const auto ads_improved = FitAdsIntoDirectory(ads_run, kHysteresisAdsStrategyName,
                                                ads_improved_dir, o.software_version);
  for (const auto* fits : {&imu_reference, &imu_joint, &ads_reference, &ads_improved}) {
    for (const WrittenConstants& w : *fits) records.AddConstants(ConstantsRecordFromFile(w.path));
  }
  observer.Stage(fmt::format("fits written: {} IMU x 2 strategies, {} ADS x 2 strategies",
                             imu_joint.size(), ads_reference.size()));

  observer.Stage("3/8 download: improved IMU and ADS constants into every unit, read back bit for "
                 "bit, committed");
  const std::vector<UnitDownload> imu_downloads =
      DownloadStation(imu_station, imu_joint_dir, records);
  const std::vector<UnitDownload> ads_downloads =
      DownloadStation(ads_station, ads_improved_dir, records);

  observer.Stage("4/8 acceptance runs in the calibrated modes, both benches concurrently");
  const auto acceptance = RunBenches(o, observer, {seq.imu_acceptance}, {seq.ads_acceptance}, stop);
  observer.Stage("acceptance runs done:" + RunsText(acceptance));
  for (const auto& bench : acceptance) result.runs.insert(result.runs.end(), bench.begin(), bench.end());
  const std::filesystem::path imu_acceptance_run = RunDir(o, seq.imu_acceptance);
  const std::filesystem::path ads_acceptance_run = RunDir(o, seq.ads_acceptance);
  const AcceptanceRun imu_judged = JudgeIntoRecords(imu_acceptance_run, o.software_version, records);
  const AcceptanceRun ads_judged = JudgeIntoRecords(ads_acceptance_run, o.software_version, records);
  observer.Stage(fmt::format("acceptance against the specification: IMU batch {}, ADS {}",
                             imu_judged.pass() ? "PASS" : "FAIL",
                             ads_judged.pass() ? "PASS" : "FAIL"));

  std::vector<EvaluatedQuantity> imu_eval, ads_eval;
  if (o.truth_dir) {
    observer.Stage("5/8 evaluation against the rig's truth: every fit through the firmware "
                   "compensator on the envelope grid");
    result.reference_evaluation = EvaluateAgainstTruth(imu_reference, *o.truth_dir,
                                                       imu_station.local_gravity_mps2,
                                                       imu_reference_dir);
    imu_eval = EvaluateAgainstTruth(imu_joint, *o.truth_dir, imu_station.local_gravity_mps2,
                                    imu_joint_dir);
    result.ads_reference_evaluation = EvaluateAgainstTruth(
        ads_reference, *o.truth_dir, ads_station.local_gravity_mps2, ads_reference_dir);
    ads_eval = EvaluateAgainstTruth(ads_improved, *o.truth_dir, ads_station.local_gravity_mps2,
                                    ads_improved_dir);
  } else {
    result.not_run.push_back("evaluation against truth: no truth directory (not a simulated rig)");
  }

  observer.Stage("6/8 diagnosis: the IMU and ADS calibration runs against the pipeline's nominal model "
                 "(adahrs diagnose) -> " + (o.out_dir / "diagnosis").string());
  result.diagnosis_dir = o.out_dir / "diagnosis";
  std::vector<std::filesystem::path> diagnosed_runs = imu_runs;
  diagnosed_runs.push_back(ads_run);
  const DiagnosisRun diagnosed = DiagnoseRuns(diagnosed_runs, std::nullopt);
  WriteDiagnosis(diagnosed, result.diagnosis_dir);
  result.diagnosis = diagnosed.units;
  if (o.truth_dir) result.diagnosis_truth = CompareDiagnosisWithTruth(diagnosed.units, *o.truth_dir);
  if (o.truth_dir && o.replay) {
    result.replay_checks = CheckDiagnosisByReplay(diagnosed, *o.truth_dir, result.diagnosis_dir,
                                                  {imu_acceptance_run, ads_acceptance_run}, o.replay);
  } else {
    result.not_run.push_back("re-simulation check of the diagnosis: needs the rig's truth and a replay function");
  }

  observer.Stage("7/8 report.html per run");
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> reports;
  for (const std::filesystem::path& run : imu_runs) reports.emplace_back(run, imu_joint_dir);
  reports.emplace_back(ads_run, ads_improved_dir);
  reports.emplace_back(imu_acceptance_run, imu_joint_dir);
  reports.emplace_back(ads_acceptance_run, ads_improved_dir);
  for (const auto& [run, fit] : reports) {
    const bool judged = run == imu_acceptance_run || run == ads_acceptance_run;
    WriteRunReport(run, fit, run / "report.html",
                   judged ? std::optional<std::filesystem::path>(run / "acceptance") : std::nullopt);
    result.run_dirs.push_back(run);
  }

  observer.Stage("8/8 production records: runs, constants versions, downloads -> " +
                 result.records_file.string());
  for (const std::filesystem::path& run : result.run_dirs) {
    records.AddRun(RunRecordFromDirectory(run));
  }

  const auto outcomes = [&](const std::vector<UnitDownload>& downloads, const std::string& strategy,
                            const std::vector<EvaluatedQuantity>& eval, const AcceptanceRun& judged,
                            const std::filesystem::path& report) {
    for (const UnitDownload& d : downloads) {
      UnitOutcome u{d.role, d.serial, strategy, d, {}, std::nullopt, report};
      for (const EvaluatedQuantity& q : eval) {
        if (q.serial == d.serial) u.evaluation.push_back(q);
      }
      for (const UnitAcceptance& a : judged.units) {
        if (a.serial == d.serial) u.acceptance = a;
      }
      result.units.push_back(std::move(u));
    }
  };
  outcomes(imu_downloads, "joint", imu_eval, imu_judged, imu_acceptance_run / "report.html");
  outcomes(ads_downloads, kHysteresisAdsStrategyName, ads_eval, ads_judged,
           ads_acceptance_run / "report.html");
  return result;
}

}  // namespace adahrs::calib
