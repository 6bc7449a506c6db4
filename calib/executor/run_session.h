// A run from the files to the end: `adahrs run --station FILE --sequence FILE --run-dir DIR`
// (StartRun) and `adahrs run --resume DIR` (ResumeRun). Loads and validates the station and the
// sequence against the station's instrument limits (refused before anything moves;
// calib/sequence/station_limits.h), takes the station's interlock thresholds and attempts
// (interlocks.h), opens the station (hil::OpenStation), identifies the batch's units and the
// instruments, writes meta.json (format v3) and the journal, starts one UnitLogger per unit and
// runs the Executor.
// Resume reads meta.json (station and sequence as the run started them) and the journal, sets
// aside torn CSV and journal tails (journaled), continues the pipeline clock after the latest
// recorded t_s, refuses a batch whose unit serials differ from the recorded ones, and restarts at
// the first step not completed.
// Left out: printing (the ProgressSink does), signal handling (the app sets `stop`).
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "calib/executor/executor.h"
#include "calib/executor/progress.h"
#include "hil/recording/recording_files.h"

namespace adahrs::calib {

struct NewRunOptions {
  std::string station_file;
  std::string sequence_file;
  std::filesystem::path run_dir;
  ExecutorOptions executor;
  /// How a new run stores imu.csv and ads.csv; a resumed run keeps the form it has.
  hil::RecordingStorage storage = hil::RecordingStorage::kGzip;
  /// When set, decorates the station's operator (a logging operator, a test's fixture
  /// disturbance); receives the operator OpenStation made and returns the one the run uses.
  std::function<std::unique_ptr<hil::Operator>(std::unique_ptr<hil::Operator>)> wrap_operator;
};

struct RunSummary {
  std::filesystem::path run_dir;
  std::string status;  ///< meta.json status at the end
  uint64_t rows = 0;   ///< rows recorded by this session
  uint64_t lost = 0;   ///< packets lost in this session, all units
};

/// Starts a new run in `options.run_dir` (which must not hold a run already). Throws
/// SequenceError / ParamError before anything moves, RunError or RunInterrupted after.
RunSummary StartRun(const NewRunOptions& options,
                    ProgressSink& progress,
                    const std::atomic<bool>& stop);

/// Resumes the run in `run_dir` from its first step not completed (`options.station_file`,
/// `sequence_file` and `run_dir` are ignored: the run's meta.json has them).
RunSummary ResumeRun(const std::filesystem::path& run_dir,
                     ProgressSink& progress,
                     const std::atomic<bool>& stop,
                     const NewRunOptions& options = {});

}  // namespace adahrs::calib
