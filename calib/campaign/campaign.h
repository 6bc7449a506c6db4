// A calibration campaign: the production chain over two benches (either may be absent), each stage
// a call into its own library, each stage's output a directory under `out_dir`: (0) identity: the
// serial each unit gives checked against the expected one (campaign_identity.h; a refused unit's
// slot is left out, the others go on); (1) calibration runs, both benches concurrently
// (bench_runs.h) -> runs/<sequence>/; (2) fits of both strategies per unit kind (campaign_fits.h)
// -> fits/<kind>-<strategy>/; (3) download of the chosen strategy's constants
// (station_download.h); (4) acceptance runs judged against the specification ->
// runs/<sequence>/acceptance/<serial>/acceptance.json, a unit that failed run again up to the
// retest policy's attempts (campaign_attempts.h) -> runs/<sequence>-attempt<N>/; (5-6) stages
// injected by the caller (CampaignOptions::before_reports, e.g. proving/demo/demo_campaign.h); (7)
// report.html per run; (8) production records -> records.sqlite. The production chain never knows
// the truth. A unit that fails acceptance is a result, not an error; a stage's errors pass through
// with its context (run, step, unit, file); a stop request (SIGINT) stops the benches safely, or is
// honoured between stages and between downloads, and throws RunInterrupted.
// Resuming: the campaign journal in `out_dir` (campaign_journal.h) records the finished stages and
// the verified downloads; called again on the same `out_dir`, the campaign keeps what is done,
// resumes an unfinished run as `adahrs run --resume` does and downloads again only a unit whose
// constants changed. The injected stages are not journaled (they run again).
// Stage by stage: docs/campaign.md, docs/demo.md ("What runs", "Directories written").
// Left out: choosing the downloaded strategy by evaluation (the options name it).
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "calib/acceptance/acceptance_judge.h"
#include "calib/campaign/campaign_fits.h"
#include "calib/campaign/station_download.h"
#include "calib/executor/executor.h"
#include "calib/executor/progress.h"
#include "calib/executor/run_session.h"
#include "calib/records/yield_records.h"

namespace adahrs::calib {

struct CampaignSequences {
  std::vector<std::string> imu_calibration;  ///< run in order, fitted together
  std::string ads_calibration;
  std::string imu_acceptance;
  std::string ads_acceptance;
};

/// What the production stages produced, handed to the injected stages before the reports.
struct CampaignArtifacts {
  std::vector<std::filesystem::path> imu_calibration_runs;
  std::filesystem::path ads_calibration_run;
  std::filesystem::path imu_acceptance_run, ads_acceptance_run;
  std::filesystem::path imu_reference_dir, imu_joint_dir, ads_reference_dir, ads_improved_dir;
  std::vector<WrittenConstants> imu_reference, imu_joint, ads_reference, ads_improved;
  /// The IMU strategy file's fits (CampaignOptions::imu_strategy a file): fits/imu-<its stem>.
  std::filesystem::path imu_file_strategy_dir;
  std::vector<WrittenConstants> imu_file_strategy;
  double imu_local_gravity_mps2 = 0.0;
  double ads_local_gravity_mps2 = 0.0;
};

struct CampaignResult;

/// Whether a campaign's IMU strategy names a strategy file rather than a built-in.
bool IsImuStrategyFile(const std::string& imu_strategy);
/// The name a campaign's IMU strategy goes by: the built-in's, or the strategy file's stem.
std::string ImuStrategyLabel(const std::string& imu_strategy);

struct CampaignOptions {
  std::filesystem::path out_dir;
  std::string imu_station_file;  ///< empty: no IMU bench
  std::string ads_station_file;  ///< empty: no ADS bench
  CampaignSequences sequences;
  /// The strategy whose constants are downloaded: IMU "joint", "reference" or an IMU strategy
  /// file (a path ending in .json, e.g. an external program's: fitted besides the two built-ins),
  /// ADS "hysteresis_compensated" or "reference".
  std::string imu_strategy = "joint";
  std::string ads_strategy = "hysteresis_compensated";
  /// Expected serial per station unit role; a unit giving another serial is refused.
  std::map<std::string, std::string> expected_serials;
  /// The specification file acceptance judges against; empty: Specification::Reference() (-A).
  std::string specification_file;
  /// Acceptance attempts per unit, the first included: a unit that FAILs is retested up to this
  /// (campaign_attempts.h).
  int max_acceptance_attempts = 1;
  std::string software_version;
  std::string operator_name;  ///< on the certificates; "" not recorded
  ExecutorOptions executor;
  /// Called once the last run on the stations has ended (e.g. to stop a virtual rig, which the
  /// analysis stages after it do not need); may be empty.
  std::function<void()> stations_done;
  /// Stages run after the acceptance judgement and before the reports (whose pages show what they
  /// write into the fit directories); they may add to `CampaignResult::not_run`. May be empty.
  std::function<void(const CampaignArtifacts&, CampaignResult&)> before_reports;
};

/// What the campaign tells its user while it runs (thread-safe: benches report concurrently).
class CampaignObserver {
 public:
  virtual ~CampaignObserver() = default;
  /// A stage starts or ends: one line.
  virtual void Stage(const std::string& text) = 0;
  /// The executor's progress sink for the bench named `bench` ("IMU bench", "ADS bench").
  virtual ProgressSink& Bench(const std::string& bench) = 0;
};

struct UnitOutcome {
  std::string role;
  std::string serial;
  std::string strategy;  ///< of the downloaded constants
  UnitDownload download;
  std::optional<UnitAcceptance> acceptance;  ///< the unit's last acceptance attempt's judgement
  std::filesystem::path report;              ///< that attempt's run's report.html
  int attempts = 0;                          ///< acceptance attempts (1: no retest)
  /// certificates/<serial>.html and .pdf (calib/report/certificate.h); no PDF: why.
  std::filesystem::path certificate;
  std::optional<std::filesystem::path> certificate_pdf;
  std::string certificate_pdf_error;
};

struct CampaignResult {
  std::vector<UnitOutcome> units;
  std::vector<std::filesystem::path> run_dirs;
  /// Every bench run as its session ended: rows recorded and packets lost.
  std::vector<RunSummary> runs;
  std::vector<std::string> not_run;  ///< stages that could not run, with the reason
  /// Units refused by their serial (role, port, serial read, serial expected), left out.
  std::vector<std::string> refused_units;
  std::filesystem::path records_file;
  /// First-pass and final yield of this campaign's judged units, from the records.
  std::optional<CampaignYield> yield;
};

CampaignResult RunCampaign(const CampaignOptions& options,
                           CampaignObserver& observer,
                           const std::atomic<bool>& stop);

}  // namespace adahrs::calib
