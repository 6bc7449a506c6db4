#include "calib/campaign/campaign.h"

#include <map>
#include <set>
#include <tuple>

#include <fmt/format.h>

#include "calib/acceptance/acceptance_file.h"
#include "calib/ads_calibration/tolerance_ads_strategy.h"
#include "calib/campaign/bench_runs.h"
#include "calib/campaign/campaign_attempts.h"
#include "calib/campaign/campaign_fits.h"
#include "calib/campaign/campaign_identity.h"
#include "calib/campaign/campaign_journal.h"
#include "calib/records/acceptance_records.h"
#include "calib/records/records_sources.h"
#include "calib/records/records_store.h"
#include "calib/report/certificate.h"
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

// One bench's runs: its station file (empty: the bench does not run) and its (sequence, run
// directory) pairs, in order.
struct BenchRuns {
  std::string station_file;
  std::vector<BenchSequenceRun> runs;
};

BenchRuns Runs(const CampaignOptions& o,
               const std::optional<hil::Station>& station,
               const std::string& station_file,
               const std::vector<std::string>& sequences) {
  BenchRuns bench;
  if (!station) return bench;
  bench.station_file = station_file;
  for (const std::string& s : sequences) bench.runs.push_back({s, RunDir(o, s)});
  return bench;
}

std::vector<std::vector<RunSummary>> RunBenches(Context& c,
                                                const BenchRuns& imu,
                                                const BenchRuns& ads) {
  std::vector<BenchPlan> benches;
  if (!imu.station_file.empty() && !imu.runs.empty()) {
    benches.push_back({kImuBench, imu.station_file, imu.runs, &c.observer.Bench(kImuBench)});
  }
  if (!ads.station_file.empty() && !ads.runs.empty()) {
    benches.push_back({kAdsBench, ads.station_file, ads.runs, &c.observer.Bench(kAdsBench)});
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

// Judges attempt `attempt` of an acceptance run, writes acceptance.json per unit into
// `run`/acceptance (kept if a resumed campaign wrote them before), records every point and the
// attempt of every unit (recording is idempotent, so a resumed judgement records nothing twice).
AcceptanceRun JudgeIntoRecords(Context& c,
                               const std::filesystem::path& run,
                               int attempt,
                               const Specification& spec,
                               const std::map<std::string, std::string>& role_of_serial) {
  const AcceptanceRun judged = JudgeAcceptance(run, spec);
  const std::vector<std::filesystem::path> files =
      AcceptanceFilesOf(judged, spec, c.o.software_version, run / "acceptance");
  for (const std::filesystem::path& file : files) {
    const AcceptanceRecords points = AcceptanceRecordsFromFile(file);
    c.records.AddAcceptance(points.source_sha256, points.points);
  }
  for (const AcceptanceAttemptRecord& a :
       AttemptRecords(c.journal.campaign_id(), attempt, judged, files, role_of_serial)) {
    c.records.AddAcceptanceAttempt(a);
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
  const auto calibration =
      RunBenches(c,
                 Runs(c.o, c.imu_station, c.imu_station_file, seq.imu_calibration),
                 Runs(c.o, c.ads_station, c.ads_station_file, {seq.ads_calibration}));
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
  const bool file_strategy = IsImuStrategyFile(o.imu_strategy);
  if (file_strategy) {
    f.imu_file_strategy_dir = o.out_dir / "fits" / ("imu-" + ImuStrategyLabel(o.imu_strategy));
  }
  if (c.journal.Done(kStageFits)) {
    c.observer.Stage("2/8 fits: done before, kept");
    f.imu_reference = ReadFitDirectory(f.imu_reference_dir);
    f.imu_joint = ReadFitDirectory(f.imu_joint_dir);
    if (file_strategy) f.imu_file_strategy = ReadFitDirectory(f.imu_file_strategy_dir);
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
    if (file_strategy) {
      c.observer.Stage("  IMU strategy file " + o.imu_strategy);
      f.imu_file_strategy = FitImuIntoDirectory(f.imu_calibration_runs,
                                                ImuStrategy::Load(o.imu_strategy),
                                                f.imu_file_strategy_dir,
                                                o.software_version);
      for (const WrittenConstants& w : f.imu_file_strategy) {
        for (const std::string& line : w.log) c.observer.Stage("  " + w.file.serial + ": " + line);
      }
    }
  }
  if (c.ads_station) {
    f.ads_reference = FitAdsIntoDirectory(
        f.ads_calibration_run, kReferenceAdsStrategyName, f.ads_reference_dir, o.software_version);
    f.ads_improved = FitAdsIntoDirectory(
        f.ads_calibration_run, kHysteresisAdsStrategyName, f.ads_improved_dir, o.software_version);
  }
  for (const auto* fits :
       {&f.imu_reference, &f.imu_joint, &f.imu_file_strategy, &f.ads_reference, &f.ads_improved}) {
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
  if (IsImuStrategyFile(o.imu_strategy)) return f.imu_file_strategy_dir;
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
      ImuStrategyLabel(c.o.imu_strategy),
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

// A unit's last acceptance attempt.
struct LastAttempt {
  UnitAcceptance acceptance;
  std::filesystem::path run;
  int attempts = 0;
};

// The acceptance runs and their judgements.
struct CampaignAcceptance {
  std::filesystem::path imu_run, ads_run;  // the first attempts (every unit)
  std::vector<std::pair<std::filesystem::path, bool>> retest_runs;  // (run, of the IMU bench)
  std::map<std::string, LastAttempt> last;                          // by serial
};

std::map<std::string, std::string> RoleOfSerial(const ImprovedDownloads& d) {
  std::map<std::string, std::string> roles;
  for (const auto* bench : {&d.imu, &d.ads}) {
    for (const UnitDownload& u : *bench) roles[u.serial] = u.role;
  }
  return roles;
}

std::set<std::string> AllRoles(const std::optional<hil::Station>& station) {
  std::set<std::string> roles;
  if (station) {
    for (const hil::UnitEntry& u : station->units) roles.insert(u.role);
  }
  return roles;
}

// The station file attempt `attempt` of a bench runs on: the campaign's for the first, else one
// naming only `roles`, written under stations/attempt<N>/.
std::string AttemptStationFile(const Context& c,
                               const std::optional<hil::Station>& station,
                               const std::string& station_file,
                               int attempt,
                               const std::set<std::string>& roles) {
  if (!station || roles.empty()) return {};
  if (attempt == 1) return station_file;
  return WriteCheckedStation(StationWithRoles(*station, roles),
                             c.o.out_dir / "stations" / fmt::format("attempt{}", attempt),
                             std::filesystem::path(station_file));
}

std::string StageOfAttempt(const char* stage, int attempt) {
  return attempt == 1 ? std::string(stage) : fmt::format("{}_attempt{}", stage, attempt);
}

// One acceptance attempt on the benches with units in `imu_roles` / `ads_roles`: runs, judges,
// records; returns the roles that failed, IMU bench then ADS bench.
std::pair<std::set<std::string>, std::set<std::string>> AcceptanceAttempt(
    Context& c,
    const Specification& spec,
    int attempt,
    const std::set<std::string>& imu_roles,
    const std::set<std::string>& ads_roles,
    const std::map<std::string, std::string>& role_of_serial,
    CampaignAcceptance& a,
    CampaignResult& result) {
  const CampaignSequences& seq = c.o.sequences;
  const std::filesystem::path imu_run = AttemptRunDir(RunDir(c.o, seq.imu_acceptance), attempt);
  const std::filesystem::path ads_run = AttemptRunDir(RunDir(c.o, seq.ads_acceptance), attempt);
  const BenchRuns imu{AttemptStationFile(c, c.imu_station, c.imu_station_file, attempt, imu_roles),
                      {{seq.imu_acceptance, imu_run}}};
  const BenchRuns ads{AttemptStationFile(c, c.ads_station, c.ads_station_file, attempt, ads_roles),
                      {{seq.ads_acceptance, ads_run}}};
  const auto runs = RunBenches(c, imu, ads);
  c.observer.Stage("acceptance runs done:" + RunsText(runs));
  c.journal.MarkDone(StageOfAttempt(kStageAcceptance, attempt));
  AddRuns(runs, result);
  std::pair<std::set<std::string>, std::set<std::string>> failed;
  std::string verdicts;
  for (const auto& [bench, run, failed_roles] :
       {std::tuple{"IMU", &imu, &failed.first}, std::tuple{"ADS", &ads, &failed.second}}) {
    if (run->station_file.empty()) continue;
    const std::filesystem::path dir = run->runs.front().run_dir;
    const AcceptanceRun judged = JudgeIntoRecords(c, dir, attempt, spec, role_of_serial);
    if (attempt > 1) a.retest_runs.emplace_back(dir, run == &imu);
    for (const UnitAcceptance& u : judged.units) {
      LastAttempt& last = a.last[u.serial];
      last = {u, dir, last.attempts + 1};
    }
    *failed_roles = FailedRoles(judged, role_of_serial);
    verdicts += fmt::format(
        " {} {} {}", bench, attempt == 1 ? "batch" : "retest", judged.pass() ? "PASS" : "FAIL");
  }
  c.journal.MarkDone(StageOfAttempt(kStageJudgement, attempt));
  c.observer.Stage(
      fmt::format("acceptance attempt {} against the specification:{}", attempt, verdicts));
  return failed;
}

// Stage 4: the acceptance runs on both benches, judged and recorded; units that failed are run
// again up to the retest policy's attempts (campaign_attempts.h).
CampaignAcceptance AcceptanceRuns(Context& c,
                                  const Specification& spec,
                                  const ImprovedDownloads& downloads,
                                  CampaignResult& result) {
  c.observer.Stage("4/8 acceptance runs in the calibrated modes, both benches concurrently");
  CampaignAcceptance a;
  a.imu_run = RunDir(c.o, c.o.sequences.imu_acceptance);
  a.ads_run = RunDir(c.o, c.o.sequences.ads_acceptance);
  const std::map<std::string, std::string> role_of_serial = RoleOfSerial(downloads);
  std::set<std::string> imu_roles = AllRoles(c.imu_station);
  std::set<std::string> ads_roles = AllRoles(c.ads_station);
  for (int attempt = 1; attempt <= c.o.max_acceptance_attempts; ++attempt) {
    if (imu_roles.empty() && ads_roles.empty()) break;
    if (attempt > 1) {
      ThrowIfStopped(c, "retest");
      c.observer.Stage(fmt::format("4/8 retest, attempt {} of {}: {} unit(s) that failed",
                                   attempt,
                                   c.o.max_acceptance_attempts,
                                   imu_roles.size() + ads_roles.size()));
    }
    std::tie(imu_roles, ads_roles) =
        AcceptanceAttempt(c, spec, attempt, imu_roles, ads_roles, role_of_serial, a, result);
  }
  if (c.o.stations_done) c.o.stations_done();
  return a;
}

// Stage 7: report.html per run with the downloaded fit of its unit kind; the acceptance runs'
// with their judgement.
void WriteReports(Context& c,
                  const CampaignArtifacts& f,
                  const CampaignAcceptance& acceptance,
                  const Specification& spec,
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
  const size_t first_judged = reports.size() - (c.imu_station ? 1 : 0) - (c.ads_station ? 1 : 0);
  for (const auto& [run, imu] : acceptance.retest_runs) {
    reports.emplace_back(run, imu ? DownloadedImuDir(c.o, f) : DownloadedAdsDir(c.o, f));
  }
  for (size_t i = 0; i < reports.size(); ++i) {
    const auto& [run, fit] = reports[i];
    const bool judged = i >= first_judged;
    WriteRunReport(run,
                   fit,
                   run / "report.html",
                   judged ? std::optional<std::filesystem::path>(run / "acceptance") : std::nullopt,
                   spec);
    result.run_dirs.push_back(run);
  }
  c.journal.MarkDone(kStageReports);
}

// Each downloaded unit with its last acceptance attempt and its certificate.
void AddUnitOutcomes(const CampaignOptions& o,
                     const std::vector<UnitDownload>& downloads,
                     const std::string& strategy,
                     const CampaignAcceptance& acceptance,
                     CampaignResult& result) {
  for (const UnitDownload& d : downloads) {
    UnitOutcome u{d.role, d.serial, strategy, d, std::nullopt, {}, 0, {}, std::nullopt, {}};
    const auto last = acceptance.last.find(d.serial);
    if (last != acceptance.last.end()) {
      u.acceptance = last->second.acceptance;
      u.report = last->second.run / "report.html";
      u.attempts = last->second.attempts;
      const WrittenCertificate c = WriteCertificate(
          ReadCertificateInputs(last->second.run / "acceptance" / d.serial / kAcceptanceFileName,
                                d.constants_file,
                                o.operator_name,
                                o.software_version),
          o.out_dir / "certificates");
      u.certificate = c.html;
      u.certificate_pdf = c.pdf;
      u.certificate_pdf_error = c.pdf_error;
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

bool IsImuStrategyFile(const std::string& imu_strategy) {
  return imu_strategy.size() > 5 && imu_strategy.ends_with(".json");
}

std::string ImuStrategyLabel(const std::string& imu_strategy) {
  return IsImuStrategyFile(imu_strategy) ? std::filesystem::path(imu_strategy).stem().string()
                                         : imu_strategy;
}

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

  const CampaignAcceptance acceptance = AcceptanceRuns(c, spec, downloads, result);
  artifacts.imu_acceptance_run = acceptance.imu_run;
  artifacts.ads_acceptance_run = acceptance.ads_run;
  if (o.before_reports) o.before_reports(artifacts, result);
  WriteReports(c, artifacts, acceptance, spec, result);

  observer.Stage("8/8 production records: runs, constants versions, downloads -> " +
                 result.records_file.string());
  for (const std::filesystem::path& run : result.run_dirs) {
    c.records.AddRun(RunRecordFromDirectory(run));
  }
  c.journal.MarkDone(kStageRecords);
  observer.Stage("certificates: one per judged unit -> " + (o.out_dir / "certificates").string());
  AddUnitOutcomes(o, downloads.imu, ImuStrategyLabel(o.imu_strategy), acceptance, result);
  AddUnitOutcomes(o, downloads.ads, o.ads_strategy, acceptance, result);
  if (!acceptance.last.empty()) result.yield = c.records.Yields(c.journal.campaign_id()).front();
  return result;
}

}  // namespace adahrs::calib
