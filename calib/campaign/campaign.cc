#include "calib/campaign/campaign.h"

#include <fmt/format.h>

#include "calib/acceptance/acceptance_file.h"
#include "calib/ads_calibration/tolerance_ads_strategy.h"
#include "calib/campaign/bench_runs.h"
#include "calib/campaign/campaign_fits.h"
#include "calib/campaign/campaign_identity.h"
#include "calib/campaign/campaign_journal.h"
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

// The journal's stage names (docs/campaign.md "Resuming").
constexpr const char* kStageCalibration = "calibration_runs";
constexpr const char* kStageFits = "fits";
constexpr const char* kStageDownloads = "downloads";
constexpr const char* kStageAcceptance = "acceptance_runs";
constexpr const char* kStageJudgement = "judgement";
constexpr const char* kStageReports = "reports";
constexpr const char* kStageRecords = "records";

// The campaign as it runs: its inputs, the benches present (after the identity check), the
// journal, the records.
struct Context {
  const CampaignOptions& o;
  CampaignObserver& observer;
  const std::atomic<bool>& stop;
  CampaignJournal journal;
  RecordsStore records;
  std::optional<hil::Station> imu_station, ads_station;
  std::string imu_station_file, ads_station_file;  // the files the runs use
};

std::filesystem::path RunDir(const CampaignOptions& o, const std::string& sequence_file) {
  return o.out_dir / "runs" / ParseSequenceFile(sequence_file).sequence.name;
}

void ThrowIfStopped(const Context& c, const char* before) {
  if (c.stop) throw RunInterrupted(std::string("stopped before the ") + before);
}

std::vector<std::vector<RunSummary>> RunBenches(Context& c,
                                                const std::vector<std::string>& imu_sequences,
                                                const std::vector<std::string>& ads_sequences) {
  std::vector<BenchPlan> benches;
  if (c.imu_station) {
    BenchPlan imu{kImuBench, c.imu_station_file, {}, &c.observer.Bench(kImuBench)};
    for (const std::string& s : imu_sequences) imu.runs.push_back({s, RunDir(c.o, s)});
    benches.push_back(std::move(imu));
  }
  if (c.ads_station) {
    BenchPlan ads{kAdsBench, c.ads_station_file, {}, &c.observer.Bench(kAdsBench)};
    for (const std::string& s : ads_sequences) ads.runs.push_back({s, RunDir(c.o, s)});
    benches.push_back(std::move(ads));
  }
  return RunBenchesConcurrently(benches, c.o.executor, c.stop);
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

// Judges an acceptance run; unless the journal says it was done, writes acceptance.json per unit
// into `run`/acceptance and records every point. Returns the judgement.
AcceptanceRun JudgeIntoRecords(Context& c,
                               const std::filesystem::path& run,
                               const Specification& spec) {
  const AcceptanceRun judged = JudgeAcceptance(run, spec);
  if (c.journal.Done(kStageJudgement)) return judged;
  for (const std::filesystem::path& file :
       WriteAcceptanceFiles(judged, spec, c.o.software_version, run / "acceptance")) {
    const AcceptanceRecords points = AcceptanceRecordsFromFile(file);
    c.records.AddAcceptance(points.source_sha256, points.points);
  }
  return judged;
}

void AddRuns(const std::vector<std::vector<RunSummary>>& benches, CampaignResult& result) {
  for (const auto& bench : benches) {
    result.runs.insert(result.runs.end(), bench.begin(), bench.end());
  }
}

// Stage 1: the calibration runs on both benches (each left as it is if complete, resumed if not).
void CalibrationRuns(Context& c, CampaignResult& result) {
  const CampaignSequences& seq = c.o.sequences;
  c.observer.Stage(
      "1/8 calibration runs: IMU calibration on the IMU bench, ADS calibration on the "
      "ADS bench, concurrently");
  const auto calibration = RunBenches(c, seq.imu_calibration, {seq.ads_calibration});
  c.observer.Stage("calibration runs done:" + RunsText(calibration));
  AddRuns(calibration, result);
  c.journal.MarkDone(kStageCalibration);
}

// Stage 2: fits every strategy into `f`'s directories and records every constants file.
void FitStrategies(Context& c, CampaignArtifacts& f) {
  const CampaignOptions& o = c.o;
  f.imu_reference_dir = o.out_dir / "fits" / "imu-reference";
  f.imu_joint_dir = o.out_dir / "fits" / "imu-joint";
  f.ads_reference_dir = o.out_dir / "fits" / "ads-reference";
  f.ads_improved_dir = o.out_dir / "fits" / "ads-hysteresis-compensated";
  if (c.journal.Done(kStageFits)) {
    c.observer.Stage("2/8 fits: done before, kept");
    f.imu_reference = ReadFitDirectory(f.imu_reference_dir);
    f.imu_joint = ReadFitDirectory(f.imu_joint_dir);
    f.ads_reference = ReadFitDirectory(f.ads_reference_dir);
    f.ads_improved = ReadFitDirectory(f.ads_improved_dir);
    return;
  }
  c.observer.Stage(
      "2/8 fits: IMU reference and improved (joint, firmware format 3) strategies, ADS "
      "reference and improved (hysteresis-compensated pressure surfaces, ISA / CAS "
      "laws) strategies");
  if (c.imu_station) {
    f.imu_reference = FitImuIntoDirectory(
        f.imu_calibration_runs, ImuStrategy::Reference(), f.imu_reference_dir, o.software_version);
    f.imu_joint = FitImuIntoDirectory(
        f.imu_calibration_runs, ImuStrategy::JointFormat3(), f.imu_joint_dir, o.software_version);
  }
  if (c.ads_station) {
    f.ads_reference = FitAdsIntoDirectory(
        f.ads_calibration_run, kReferenceAdsStrategyName, f.ads_reference_dir, o.software_version);
    f.ads_improved = FitAdsIntoDirectory(
        f.ads_calibration_run, kHysteresisAdsStrategyName, f.ads_improved_dir, o.software_version);
  }
  for (const auto* fits : {&f.imu_reference, &f.imu_joint, &f.ads_reference, &f.ads_improved}) {
    for (const WrittenConstants& w : *fits) c.records.AddConstants(ConstantsRecordFromFile(w.path));
  }
  c.observer.Stage(fmt::format("fits written: {} IMU x 2 strategies, {} ADS x 2 strategies",
                               f.imu_joint.size(),
                               f.ads_reference.size()));
  c.journal.MarkDone(kStageFits);
}

struct ImprovedDownloads {
  std::vector<UnitDownload> imu, ads;
};

// The fit directory of the downloaded strategy of each kind.
std::filesystem::path DownloadedImuDir(const CampaignOptions& o, const CampaignArtifacts& f) {
  return o.imu_strategy == "reference" ? f.imu_reference_dir : f.imu_joint_dir;
}
std::filesystem::path DownloadedAdsDir(const CampaignOptions& o, const CampaignArtifacts& f) {
  return o.ads_strategy == kReferenceAdsStrategyName ? f.ads_reference_dir : f.ads_improved_dir;
}

// Stage 3: the chosen constants into every unit of both stations, each unit once per constants.
ImprovedDownloads DownloadConstantsStage(Context& c, const CampaignArtifacts& f) {
  c.observer.Stage(fmt::format(
      "3/8 download: IMU {} and ADS {} constants into every unit, read back bit for bit, "
      "committed",
      c.o.imu_strategy,
      c.o.ads_strategy));
  DownloadLedger ledger;
  ledger.verified_before = [&c](const std::string& serial, const std::string& sha256) {
    std::optional<UnitDownload> before = c.journal.VerifiedDownload(serial, sha256);
    if (before) {
      c.observer.Stage(fmt::format(
          "  {} {}: these constants verified before, not downloaded again", before->role, serial));
    }
    return before;
  };
  ledger.verified = [&c](const UnitDownload& d) { c.journal.RecordDownload(d); };
  ImprovedDownloads d;
  if (c.imu_station) {
    d.imu = DownloadStation(*c.imu_station, DownloadedImuDir(c.o, f), c.records, ledger, &c.stop);
  }
  if (c.ads_station) {
    d.ads = DownloadStation(*c.ads_station, DownloadedAdsDir(c.o, f), c.records, ledger, &c.stop);
  }
  c.journal.MarkDone(kStageDownloads);
  return d;
}

// The acceptance runs and their judgements.
struct CampaignAcceptance {
  std::filesystem::path imu_run, ads_run;
  AcceptanceRun imu_judged, ads_judged;
};

// Stage 4: the acceptance runs on both benches, judged and recorded.
CampaignAcceptance AcceptanceRuns(Context& c, const Specification& spec, CampaignResult& result) {
  const CampaignSequences& seq = c.o.sequences;
  c.observer.Stage("4/8 acceptance runs in the calibrated modes, both benches concurrently");
  const auto acceptance = RunBenches(c, {seq.imu_acceptance}, {seq.ads_acceptance});
  c.observer.Stage("acceptance runs done:" + RunsText(acceptance));
  c.journal.MarkDone(kStageAcceptance);
  if (c.o.stations_done) c.o.stations_done();
  AddRuns(acceptance, result);
  CampaignAcceptance a;
  std::string verdicts;
  if (c.imu_station) {
    a.imu_run = RunDir(c.o, seq.imu_acceptance);
    a.imu_judged = JudgeIntoRecords(c, a.imu_run, spec);
    verdicts += fmt::format(" IMU batch {}", a.imu_judged.pass() ? "PASS" : "FAIL");
  }
  if (c.ads_station) {
    a.ads_run = RunDir(c.o, seq.ads_acceptance);
    a.ads_judged = JudgeIntoRecords(c, a.ads_run, spec);
    verdicts += fmt::format(" ADS {}", a.ads_judged.pass() ? "PASS" : "FAIL");
  }
  c.journal.MarkDone(kStageJudgement);
  c.observer.Stage("acceptance against the specification:" + verdicts);
  return a;
}

// Stage 7: report.html per run with the downloaded fit of its unit kind; the acceptance runs'
// with their judgement.
void WriteReports(Context& c,
                  const CampaignArtifacts& f,
                  const CampaignAcceptance& acceptance,
                  CampaignResult& result) {
  c.observer.Stage("7/8 report.html per run");
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> reports;
  if (c.imu_station) {
    for (const std::filesystem::path& run : f.imu_calibration_runs) {
      reports.emplace_back(run, DownloadedImuDir(c.o, f));
    }
  }
  if (c.ads_station) reports.emplace_back(f.ads_calibration_run, DownloadedAdsDir(c.o, f));
  if (c.imu_station) reports.emplace_back(acceptance.imu_run, DownloadedImuDir(c.o, f));
  if (c.ads_station) reports.emplace_back(acceptance.ads_run, DownloadedAdsDir(c.o, f));
  for (const auto& [run, fit] : reports) {
    const bool judged = run == acceptance.imu_run || run == acceptance.ads_run;
    WriteRunReport(
        run,
        fit,
        run / "report.html",
        judged ? std::optional<std::filesystem::path>(run / "acceptance") : std::nullopt);
    result.run_dirs.push_back(run);
  }
  c.journal.MarkDone(kStageReports);
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

// Loads a bench's station, checks its units' serials, and sets the station file its runs use.
void PrepareBench(Context& c,
                  const std::string& station_file,
                  const char* bench,
                  std::optional<hil::Station>& station,
                  std::string& run_station_file,
                  CampaignResult& result) {
  if (station_file.empty()) return;
  station = hil::Station::Load(station_file);
  run_station_file = station_file;
  const IdentityCheck check = CheckUnitIdentities(*station, c.o.expected_serials);
  for (const std::string& refusal : check.refused) {
    c.observer.Stage(std::string("  ") + bench + ": " + refusal);
    result.refused_units.push_back(refusal);
  }
  if (check.refused.empty()) return;
  if (check.station.units.empty()) {
    result.not_run.push_back(std::string(bench) + ": every unit refused by its serial");
    station.reset();
    return;
  }
  station = check.station;
  run_station_file =
      WriteCheckedStation(*station, c.o.out_dir / "stations", std::filesystem::path(station_file));
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
  std::filesystem::create_directories(o.out_dir);
  result.records_file = o.out_dir / "records.sqlite";
  Context c{o,
            observer,
            stop,
            CampaignJournal(o.out_dir),
            RecordsStore(result.records_file),
            std::nullopt,
            std::nullopt,
            {},
            {}};
  RequireExpectedRolesExist(o.expected_serials, o.imu_station_file, o.ads_station_file);
  observer.Stage("0/8 identity: every unit's serial read from the unit" +
                 std::string(o.expected_serials.empty() ? " (no serial expected)"
                                                        : ", checked against the expected one"));
  PrepareBench(c, o.imu_station_file, kImuBench, c.imu_station, c.imu_station_file, result);
  PrepareBench(c, o.ads_station_file, kAdsBench, c.ads_station, c.ads_station_file, result);
  if (!c.imu_station && !c.ads_station) {
    throw RunError("no bench to run: " + (result.not_run.empty() ? std::string("no station given")
                                                                 : result.not_run.front()));
  }

  CampaignArtifacts artifacts;
  if (c.imu_station) {
    artifacts.imu_local_gravity_mps2 = c.imu_station->local_gravity_mps2;
    for (const std::string& s : o.sequences.imu_calibration) {
      artifacts.imu_calibration_runs.push_back(RunDir(o, s));
    }
  }
  if (c.ads_station) {
    artifacts.ads_local_gravity_mps2 = c.ads_station->local_gravity_mps2;
    artifacts.ads_calibration_run = RunDir(o, o.sequences.ads_calibration);
  }
  if (c.journal.Done(kStageCalibration)) {
    observer.Stage("1/8 calibration runs: done before, kept");
  } else {
    CalibrationRuns(c, result);
  }
  ThrowIfStopped(c, "fits");
  FitStrategies(c, artifacts);
  ThrowIfStopped(c, "download");
  const ImprovedDownloads downloads = DownloadConstantsStage(c, artifacts);
  ThrowIfStopped(c, "acceptance runs");

  const CampaignAcceptance acceptance = AcceptanceRuns(c, spec, result);
  artifacts.imu_acceptance_run = acceptance.imu_run;
  artifacts.ads_acceptance_run = acceptance.ads_run;
  if (o.before_reports) o.before_reports(artifacts, result);
  WriteReports(c, artifacts, acceptance, result);

  observer.Stage("8/8 production records: runs, constants versions, downloads -> " +
                 result.records_file.string());
  for (const std::filesystem::path& run : result.run_dirs) {
    c.records.AddRun(RunRecordFromDirectory(run));
  }
  c.journal.MarkDone(kStageRecords);
  AddUnitOutcomes(downloads.imu,
                  o.imu_strategy,
                  acceptance.imu_judged,
                  acceptance.imu_run / "report.html",
                  result);
  AddUnitOutcomes(downloads.ads,
                  o.ads_strategy,
                  acceptance.ads_judged,
                  acceptance.ads_run / "report.html",
                  result);
  return result;
}

}  // namespace adahrs::calib
