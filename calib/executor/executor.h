// The run executor: a state machine over the PlannedActions of calib::ExpandSequence for one batch
// (1–4 IMUs, or 1+ ADS units), logged in parallel by one UnitLogger thread per unit. Each action
// runs to a real condition read from the instruments (hil/instruments/instruments.h), polled on the
// pipeline clock with a wall-time floor, every wait bounded by timeout_factor × the plan estimate +
// margin; a timeout ends the run with a RunError naming the step, the instrument and the last
// reading. Nothing is ever a fixed sleep standing in for a condition. Acquisitions set every unit's
// TAG to the step's TAG and back to 0; interlocks (interlocks.h) run before accelerometer and gyro
// acquisitions, with up to `interlock_attempts` re-mounts. On any error, stop request or the end,
// the rig is made safe and meta.json and the journal are synced.
// Units: seconds of pipeline clock unless a name says wall.
// The waits, margins, interlock handling, journal and safe stop: docs/executor.md ("State
// machine", "Interlocks", "Safety", "Journal and durability").
// Left out: opening the station and the files (run_session.h), changing unit modes.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "calib/executor/interlocks.h"
#include "calib/executor/journal.h"
#include "calib/executor/progress.h"
#include "calib/executor/run_annotations.h"
#include "calib/executor/run_meta.h"
#include "calib/executor/unit_logger.h"
#include "calib/sequence/execution_plan.h"
#include "hil/clock.h"
#include "hil/instruments/instruments.h"

namespace adahrs::calib {

/// The run stopped on an error; what() names the step, the action and the instrument or unit.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The run stopped because a stop was requested (SIGINT); it can be resumed.
class RunInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ExecutorOptions {
  double poll_interval_s = 0.25;    ///< clock seconds between condition polls
  double refresh_interval_s = 1.0;  ///< clock seconds between instrument readings for the rows
  double timeout_factor = 3.0;      ///< wait timeout = factor × estimate + margin
  /// The chamber's mean rate to a new set point, as the plan's default (PlanTiming): a chamber
  /// wait is budgeted from the process value it starts at, at this rate, when that is longer
  /// (the station's declared rates only shorten the plan's estimate, never this floor).
  double chamber_ramp_c_per_min = PlanTiming{}.chamber_ramp_c_per_min;
  double timeout_margin_s = 60.0;  ///< clock seconds
  double min_margin_wall_s = 3.0;  ///< wall seconds the margin never falls below
  double min_poll_wall_s = 0.005;  ///< wall seconds between polls at least
  int interlock_attempts = 3;      ///< interlock tries (with a prompt between) before aborting
  InterlockThresholds interlock_thresholds;  ///< what the interlocks accept
  double interlock_sample_s = 1.0;           ///< packets averaged by an interlock check
  double packet_rate_hz = 100.0;
  double jog_accel_dps2 = 100.0;  ///< table acceleration of the gyro interlock's jog
  double safe_stop_accel_dps2 = 100.0;
  double table_rate_tolerance_dps = 0.01;  ///< at rate: reported rate within this of the command
  double progress_interval_s = 0.5;        ///< wall seconds between progress reports
};

/// The instruments a batch uses (not owned); null where the station has none.
struct BatchInstruments {
  hil::RateTable* rate_table = nullptr;
  hil::Chamber* chamber = nullptr;  ///< the IMU chamber for IMU sequences, the ADS one for ADS
  hil::AirDataTestSet* adts = nullptr;
  hil::Operator* op = nullptr;
};

class Executor {
 public:
  /// Everything must outlive the executor; `loggers` are running. `stop` is polled.
  Executor(const Sequence& sequence,
           const ExecutionPlan& plan,
           BatchInstruments instruments,
           std::vector<UnitLogger*> loggers,
           const hil::Clock& clock,
           RunAnnotations& annotations,
           SharedRecording& recording,
           Journal& journal,
           RunMeta& meta,
           ProgressSink& progress,
           const std::atomic<bool>& stop,
           ExecutorOptions options = {});

  /// Runs the plan from the first action of step `first_step` to the end, then makes the rig
  /// safe and sets status "complete". On a resume (`resumed_from_s` set) the rig state the
  /// earlier steps left (orientation, chamber set point, ADTS aims) is restored first and the
  /// rows since `resumed_from_s` become a "repeated partial step" rejected interval. Throws
  /// RunError or RunInterrupted after making the rig safe and setting the status.
  void Run(size_t first_step, std::optional<double> resumed_from_s);

 private:
  void RunActions(size_t first_action);
  void Execute(const PlannedAction& a);
  void RestoreState(size_t first_action);
  /// Before anything else of a run or a resume: what a killed run may have left moving is brought
  /// to a known state (table stopped and at rest, chamber profile stopped holding its set point,
  /// ADTS to ground), so no step starts on a spinning table. A table that does not come to rest
  /// stops the run.
  void SafeStart();
  void StopTableAndWait();
  void MakeSafe();

  void Mount(int orientation);
  void StartAcquisitions(uint8_t tag, int64_t quota);
  void EndAcquisitions();
  void Acquire(const PlannedAction& a, int64_t packets);
  void LogFor(const PlannedAction& a, double duration_s);
  void RunProfile(const PlannedAction& a, const std::string& name);
  void GravityInterlock(const PlannedAction& a, int orientation);
  void GyroInterlock(const PlannedAction& a, int orientation, double jog_rate_dps);
  void InterlockFailed(const PlannedAction& a,
                       const std::string& kind,
                       double t_start_s,
                       const std::vector<std::string>& failures,
                       int attempt,
                       int orientation);
  std::vector<RawAverage> AverageAll(const PlannedAction& a);
  void WaitTableAt(double rate_dps, double estimate_s);
  void WaitChamberInBand(double target_c, double band_c, double soak_s, double estimate_s);
  void WaitAdtsStable(double estimate_s);

  /// Polls `done` every poll interval until true; throws RunError naming `what` and `state()` on
  /// timeout; checks the stop flag and the loggers' health, refreshes the readings, reports.
  template <typename Done, typename State>
  void WaitFor(const std::string& what, double estimate_s, Done done, State state);
  void Tick();
  /// Clock seconds between polls and the wait margin, with their wall-time floors (header).
  double PollIntervalS() const;
  double TimeoutMarginS() const;
  void RefreshReadings();
  void Report(bool force);
  std::string Where() const;
  std::string ChamberRole() const;

  hil::RateTable& Table();
  hil::Chamber& Chamber();
  hil::AirDataTestSet& Adts();

  const Sequence& sequence_;
  const ExecutionPlan& plan_;
  BatchInstruments instruments_;
  std::vector<UnitLogger*> loggers_;
  std::vector<std::string> roles_;
  const hil::Clock& clock_;
  RunAnnotations& annotations_;
  SharedRecording& recording_;
  Journal& journal_;
  RunMeta& meta_;
  ProgressSink& progress_;
  const std::atomic<bool>& stop_;
  ExecutorOptions options_;

  std::vector<std::optional<GravityReference>> gravity_references_;  // per unit
  size_t current_action_ = 0;
  double action_started_s_ = 0.0;
  std::optional<double> measured_remaining_s_;  // of the running action, when it measures one
  double last_refresh_s_ = -1e300;
  std::chrono::steady_clock::time_point last_report_{};
};

}  // namespace adahrs::calib
