// Runs the sequences of independent benches at the same time (an IMU bench and an ADS bench share
// no instrument and no unit): one thread per bench, each running its sequences one after the
// other with StartRun (run_session.h), each into its own run directory. When a run of one bench
// fails or is interrupted, the other bench is asked to stop too (it leaves its rig safe and its run
// resumable, as Ctrl-C does), and the first failure is rethrown once both threads have ended.
// A run directory that already holds a run is continued, not refused: a complete run is left as it
// is (its summary counts no rows), any other is resumed with ResumeRun from its first step not
// completed, as `adahrs run --resume` does. That is how a campaign resumes its bench stages.
// Left out: more than one batch per bench.
#pragma once

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

#include "calib/executor/progress.h"
#include "calib/executor/run_session.h"

namespace adahrs::calib {

struct BenchSequenceRun {
  std::string sequence_file;
  std::filesystem::path run_dir;
};

struct BenchPlan {
  std::string name;  ///< "IMU bench", for messages
  std::string station_file;
  std::vector<BenchSequenceRun> runs;  ///< run in this order
  ProgressSink* progress = nullptr;    ///< this bench's reports (must be thread-safe with others)
};

/// Runs every bench's sequences, benches concurrently; returns the summaries bench by bench, run
/// by run. Throws the first failure (prefixed with the bench name and run directory) after every
/// bench has stopped; `stop` (e.g. SIGINT) stops all benches.
std::vector<std::vector<RunSummary>> RunBenchesConcurrently(const std::vector<BenchPlan>& benches,
                                                            const ExecutorOptions& options,
                                                            const std::atomic<bool>& stop);

}  // namespace adahrs::calib
