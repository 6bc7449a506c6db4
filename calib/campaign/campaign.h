// A calibration campaign: the production chain over two benches, each stage a call into its own
// library, each stage's output a directory under `out_dir` (docs/demo.md):
//   1. calibration runs, IMU bench and ADS bench concurrently (bench_runs.h):
//      the IMU calibration sequences in order (one thermal + sensor run, or a thermal calibration
//      then a sensor calibration); ADS calibration;                            -> runs/<sequence>/
//   2. fits (campaign_fits.h): IMU reference and improved (joint, firmware format 3: scale
//      factors in temperature, axis nonlinearity, g-sensitivity) strategies, ADS reference and
//      improved (hysteresis_compensated: pressure surfaces with the firmware's ISA / CAS laws and
//      hysteresis operators, tolerance_ads_strategy.h) strategies
//                                                                -> fits/<kind>-<strategy>/
//   3. download of the chosen constants (improved IMU, improved ADS) into every unit, read-back
//      verified, recorded (station_download.h)
//   4. acceptance runs in the calibrated modes, both benches concurrently      -> runs/<sequence>/
//      each judged against the reference specification (calib/acceptance/acceptance_judge.h)
//                                                ->
//                                                runs/<sequence>/acceptance/<serial>/acceptance.json
//   5. evaluation against the simulator's truth when `truth_dir` is given (truth_evaluation.h),
//      for every fit                                     -> fits/<…>/evaluation.json
//   6. diagnosis of the IMU and ADS calibration runs against the pipeline's nominal model
//      (calib/diagnosis), beside the truth when `truth_dir` is given (diagnosis_truth.h)
//                                                          -> diagnosis/diagnosis.json, report.html
//      and, with a truth directory and a replay function, the held-out check: each unit's truth
//      without the vocabulary's effects (the base) and it with the findings (model.json), the
//      acceptance runs re-simulated with either and compared with their recordings
//                          -> diagnosis/models/<serial>/{base,model}.json,
//                          diagnosis/replay_check.{json,html}
//   7. report.html per run (run_report.h) with the fit of its unit kind
//   8. production records: every run, every constants file, every download -> records.sqlite
// Stages that cannot run are listed in CampaignResult::not_run with the reason, never faked
// (evaluation against truth on a real rig). A unit that fails acceptance is a result, not an error:
// the campaign goes on to evaluation, reports and records.
// Errors of a stage pass through with its own context (run, step, unit, file); a stop request
// (SIGINT) stops the benches safely and throws RunInterrupted.
// Left out: resuming a campaign (each run resumes with `adahrs run --resume`), choosing the
// downloaded strategy by evaluation (the improved one is downloaded by design).
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "calib/acceptance/acceptance_judge.h"
#include "calib/campaign/diagnosis_truth.h"
#include "calib/campaign/station_download.h"
#include "calib/campaign/truth_evaluation.h"
#include "calib/diagnosis/imu_diagnosis.h"
#include "calib/diagnosis/replay_comparison.h"
#include "calib/executor/executor.h"
#include "calib/executor/progress.h"
#include "calib/executor/run_session.h"

namespace adahrs::calib {

struct CampaignSequences {
  std::vector<std::string> imu_calibration;  ///< run in order, fitted together
  std::string ads_calibration;
  std::string imu_acceptance;
  std::string ads_acceptance;
};

struct CampaignOptions {
  std::filesystem::path out_dir;
  std::string imu_station_file;
  std::string ads_station_file;
  CampaignSequences sequences;
  std::optional<std::filesystem::path> truth_dir;  ///< simulated rigs only
  std::string software_version;
  ExecutorOptions executor;
  /// Re-simulates a run with unit files (the application's rig_sim::ReplayRecording); empty: the
  /// held-out re-simulation check is not run.
  ReplayFunction replay;
  /// Called once the last run on the stations has ended (e.g. to stop a virtual rig, which the
  /// analysis stages after it do not need); may be empty.
  std::function<void()> stations_done;
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
  std::vector<EvaluatedQuantity> evaluation;  ///< of the downloaded constants (empty: no truth)
  std::optional<UnitAcceptance> acceptance;   ///< the unit's acceptance judgement
  std::filesystem::path report;               ///< the acceptance run's report.html
};

struct CampaignResult {
  std::vector<UnitOutcome> units;
  /// The IMU calibration runs diagnosed against the pipeline's nominal model (diagnosis/).
  std::vector<UnitDiagnosis> diagnosis;
  std::vector<DiagnosisTruthLine> diagnosis_truth;  ///< empty without a truth directory
  /// The acceptance runs re-simulated with the base and the augmented models (empty without a
  /// truth directory or a replay function).
  std::vector<ReplayComparison> replay_checks;
  std::filesystem::path diagnosis_dir;
  std::vector<std::filesystem::path> run_dirs;
  /// Every bench run as its session ended: rows recorded and packets lost.
  std::vector<RunSummary> runs;
  std::vector<EvaluatedQuantity> reference_evaluation;  ///< IMU reference strategy, for comparison
  std::vector<EvaluatedQuantity> ads_reference_evaluation;  ///< ADS reference strategy, likewise
  std::vector<std::string> not_run;  ///< stages without a library in this build, with the reason
  std::filesystem::path records_file;
};

CampaignResult RunCampaign(const CampaignOptions& options,
                           CampaignObserver& observer,
                           const std::atomic<bool>& stop);

}  // namespace adahrs::calib
