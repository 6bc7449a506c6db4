#include "calib/campaign/campaign.h"

#include <fmt/format.h>

#include "calib/acceptance/acceptance_file.h"
#include "calib/ads_calibration/tolerance_ads_strategy.h"
#include "calib/campaign/bench_runs.h"
#include "calib/campaign/campaign_fits.h"
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

std::vector<std::vector<RunSummary>> RunBenches(const CampaignOptions& o,
                                                CampaignObserver& observer,
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
      text += fmt::format(
          "\n  {}: {}, {} rows, {} packets lost", s.run_dir.string(), s.status, s.rows, s.lost);
    }
  }
  return text;
}

// Judges an acceptance run, writes acceptance.json per unit into `run`/acceptance and records
// every point; returns the judgement.
AcceptanceRun JudgeIntoRecords(const std::filesystem::path& run,
                               const Specification& spec,
                               const std::string& software_version,
                               RecordsStore& records) {
  const AcceptanceRun judged = JudgeAcceptance(run, spec);
  for (const std::filesystem::path& file :
       WriteAcceptanceFiles(judged, spec, software_version, run / "acceptance")) {
    const AcceptanceRecords points = AcceptanceRecordsFromFile(file);
    records.AddAcceptance(points.source_sha256, points.points);
  }
  return judged;
}

void AddRuns(const std::vector<std::vector<RunSummary>>& benches, CampaignResult& result) {
  for (const auto& bench : benches) {
    result.runs.insert(result.runs.end(), bench.begin(), bench.end());
  }
}

// Stage 1: the calibration runs on both benches; returns the IMU runs' directories in order.
std::vector<std::filesystem::path> CalibrationRuns(const CampaignOptions& o,
                                                   CampaignObserver& observer,
                                                   const std::atomic<bool>& stop,
                                                   CampaignResult& result) {
  const CampaignSequences& seq = o.sequences;
  observer.Stage(
      "1/8 calibration runs: IMU calibration on the IMU bench, ADS calibration on the "
      "ADS bench, concurrently");
  const auto calibration =
      RunBenches(o, observer, seq.imu_calibration, {seq.ads_calibration}, stop);
  observer.Stage("calibration runs done:" + RunsText(calibration));
  AddRuns(calibration, result);
  std::vector<std::filesystem::path> imu_runs;
  for (const std::string& s : seq.imu_calibration) imu_runs.push_back(RunDir(o, s));
  return imu_runs;
}

// Stage 2: fits every strategy into `f`'s directories and records every constants file.
void FitStrategies(const CampaignOptions& o,
                   CampaignObserver& observer,
                   CampaignArtifacts& f,
                   RecordsStore& records) {
  const std::vector<std::filesystem::path>& imu_runs = f.imu_calibration_runs;
  const std::filesystem::path& ads_run = f.ads_calibration_run;
  observer.Stage(
      "2/8 fits: IMU reference and improved (joint, firmware format 3) strategies, ADS "
      "reference and improved (hysteresis-compensated pressure surfaces, ISA / CAS "
      "laws) strategies");
  f.imu_reference_dir = o.out_dir / "fits" / "imu-reference";
  f.imu_joint_dir = o.out_dir / "fits" / "imu-joint";
  f.ads_reference_dir = o.out_dir / "fits" / "ads-reference";
  f.ads_improved_dir = o.out_dir / "fits" / "ads-hysteresis-compensated";
  f.imu_reference = FitImuIntoDirectory(
      imu_runs, ImuStrategy::Reference(), f.imu_reference_dir, o.software_version);
  f.imu_joint = FitImuIntoDirectory(
      imu_runs, ImuStrategy::JointFormat3(), f.imu_joint_dir, o.software_version);
  f.ads_reference = FitAdsIntoDirectory(
      ads_run, kReferenceAdsStrategyName, f.ads_reference_dir, o.software_version);
  f.ads_improved = FitAdsIntoDirectory(
      ads_run, kHysteresisAdsStrategyName, f.ads_improved_dir, o.software_version);
  for (const auto* fits : {&f.imu_reference, &f.imu_joint, &f.ads_reference, &f.ads_improved}) {
    for (const WrittenConstants& w : *fits) records.AddConstants(ConstantsRecordFromFile(w.path));
  }
  observer.Stage(fmt::format("fits written: {} IMU x 2 strategies, {} ADS x 2 strategies",
                             f.imu_joint.size(),
                             f.ads_reference.size()));
}

struct ImprovedDownloads {
  std::vector<UnitDownload> imu, ads;
};

// Stage 3: the improved constants into every unit of both stations.
ImprovedDownloads DownloadImprovedConstants(CampaignObserver& observer,
                                            const hil::Station& imu_station,
                                            const hil::Station& ads_station,
                                            const CampaignArtifacts& f,
                                            RecordsStore& records) {
  observer.Stage(
      "3/8 download: improved IMU and ADS constants into every unit, read back bit for "
      "bit, committed");
  ImprovedDownloads d;
  d.imu = DownloadStation(imu_station, f.imu_joint_dir, records);
  d.ads = DownloadStation(ads_station, f.ads_improved_dir, records);
  return d;
}

// The acceptance runs and their judgements.
struct CampaignAcceptance {
  std::filesystem::path imu_run, ads_run;
  AcceptanceRun imu_judged, ads_judged;
};

// Stage 4: the acceptance runs on both benches, judged and recorded.
CampaignAcceptance AcceptanceRuns(const CampaignOptions& o,
                                  const Specification& spec,
                                  CampaignObserver& observer,
                                  const std::atomic<bool>& stop,
                                  RecordsStore& records,
                                  CampaignResult& result) {
  const CampaignSequences& seq = o.sequences;
  observer.Stage("4/8 acceptance runs in the calibrated modes, both benches concurrently");
  const auto acceptance = RunBenches(o, observer, {seq.imu_acceptance}, {seq.ads_acceptance}, stop);
  observer.Stage("acceptance runs done:" + RunsText(acceptance));
  if (o.stations_done) o.stations_done();
  AddRuns(acceptance, result);
  CampaignAcceptance a;
  a.imu_run = RunDir(o, seq.imu_acceptance);
  a.ads_run = RunDir(o, seq.ads_acceptance);
  a.imu_judged = JudgeIntoRecords(a.imu_run, spec, o.software_version, records);
  a.ads_judged = JudgeIntoRecords(a.ads_run, spec, o.software_version, records);
  observer.Stage(fmt::format("acceptance against the specification: IMU batch {}, ADS {}",
                             a.imu_judged.pass() ? "PASS" : "FAIL",
                             a.ads_judged.pass() ? "PASS" : "FAIL"));
  return a;
}

// Stage 7: report.html per run with the improved fit of its unit kind; the acceptance runs' with
// their judgement.
void WriteReports(CampaignObserver& observer,
                  const std::vector<std::filesystem::path>& imu_runs,
                  const std::filesystem::path& ads_run,
                  const CampaignArtifacts& f,
                  const CampaignAcceptance& acceptance,
                  CampaignResult& result) {
  observer.Stage("7/8 report.html per run");
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> reports;
  for (const std::filesystem::path& run : imu_runs) reports.emplace_back(run, f.imu_joint_dir);
  reports.emplace_back(ads_run, f.ads_improved_dir);
  reports.emplace_back(acceptance.imu_run, f.imu_joint_dir);
  reports.emplace_back(acceptance.ads_run, f.ads_improved_dir);
  for (const auto& [run, fit] : reports) {
    const bool judged = run == acceptance.imu_run || run == acceptance.ads_run;
    WriteRunReport(
        run,
        fit,
        run / "report.html",
        judged ? std::optional<std::filesystem::path>(run / "acceptance") : std::nullopt);
    result.run_dirs.push_back(run);
  }
}

// Each downloaded unit with its acceptance judgement.
void AddUnitOutcomes(const std::vector<UnitDownload>& downloads,
                     const std::string& strategy,
                     const AcceptanceRun& judged,
                     const std::filesystem::path& report,
                     CampaignResult& result) {
  for (const UnitDownload& d : downloads) {
    UnitOutcome u{d.role, d.serial, strategy, d, std::nullopt, report};
    for (const UnitAcceptance& a : judged.units) {
      if (a.serial == d.serial) u.acceptance = a;
    }
    result.units.push_back(std::move(u));
  }
}

}  // namespace

CampaignResult RunCampaign(const CampaignOptions& o,
                           CampaignObserver& observer,
                           const std::atomic<bool>& stop) {
  CampaignResult result;
  // Read before anything runs: a bad specification file stops the campaign, not its judgement.
  const Specification spec = o.specification_file.empty()
                                 ? Specification::Reference()
                                 : ReadSpecificationFile(o.specification_file);
  const hil::Station imu_station = hil::Station::Load(o.imu_station_file);
  const hil::Station ads_station = hil::Station::Load(o.ads_station_file);
  result.records_file = o.out_dir / "records.sqlite";
  RecordsStore records(result.records_file);

  CampaignArtifacts artifacts;
  artifacts.imu_local_gravity_mps2 = imu_station.local_gravity_mps2;
  artifacts.ads_local_gravity_mps2 = ads_station.local_gravity_mps2;
  artifacts.imu_calibration_runs = CalibrationRuns(o, observer, stop, result);
  artifacts.ads_calibration_run = RunDir(o, o.sequences.ads_calibration);
  FitStrategies(o, observer, artifacts, records);

  const ImprovedDownloads downloads =
      DownloadImprovedConstants(observer, imu_station, ads_station, artifacts, records);

  const CampaignAcceptance acceptance = AcceptanceRuns(o, spec, observer, stop, records, result);
  artifacts.imu_acceptance_run = acceptance.imu_run;
  artifacts.ads_acceptance_run = acceptance.ads_run;
  if (o.before_reports) o.before_reports(artifacts, result);
  WriteReports(observer,
               artifacts.imu_calibration_runs,
               artifacts.ads_calibration_run,
               artifacts,
               acceptance,
               result);

  observer.Stage("8/8 production records: runs, constants versions, downloads -> " +
                 result.records_file.string());
  for (const std::filesystem::path& run : result.run_dirs) {
    records.AddRun(RunRecordFromDirectory(run));
  }
  AddUnitOutcomes(
      downloads.imu, "joint", acceptance.imu_judged, acceptance.imu_run / "report.html", result);
  AddUnitOutcomes(downloads.ads,
                  kHysteresisAdsStrategyName,
                  acceptance.ads_judged,
                  acceptance.ads_run / "report.html",
                  result);
  return result;
}

}  // namespace adahrs::calib
