#include "calib/campaign/bench_runs.h"

#include <chrono>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "calib/executor/run_meta.h"
#include "common/param_reader.h"

namespace adahrs::calib {
namespace {

// How often the forwarding thread passes an outside stop request on to the benches.
constexpr auto kStopPollInterval = std::chrono::milliseconds(50);

// The first failure of any bench, rethrown with the bench and run that failed.
class FirstFailure {
 public:
  void Record(const std::string& where) {
    std::lock_guard lock(mutex_);
    if (error_) return;
    try {
      throw;
    } catch (const RunInterrupted& e) {
      error_ = std::make_exception_ptr(RunInterrupted(where + ": " + e.what()));
    } catch (const std::exception& e) {
      error_ = std::make_exception_ptr(RunError(where + ": " + e.what()));
    }
  }
  void RethrowIfAny() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  std::mutex mutex_;
  std::exception_ptr error_;
};

// The run in `run_dir` as the campaign finds it: started fresh, resumed (ResumeRun, as `adahrs run
// --resume` does), or, complete already, left as it is.
RunSummary StartOrContinue(const BenchPlan& bench,
                           const BenchSequenceRun& run,
                           const ExecutorOptions& options,
                           const std::atomic<bool>& stop) {
  NewRunOptions run_options;
  run_options.station_file = bench.station_file;
  run_options.sequence_file = run.sequence_file;
  run_options.run_dir = run.run_dir;
  run_options.executor = options;
  const std::filesystem::path meta = run.run_dir / "meta.json";
  if (!std::filesystem::exists(meta)) return StartRun(run_options, *bench.progress, stop);
  const std::string status = common::ParamReader::LoadFile(meta.string()).value("status", "");
  if (status == kStatusComplete) return RunSummary{run.run_dir, status, 0, 0};
  bench.progress->Note("resuming the " + status + " run " + run.run_dir.string());
  return ResumeRun(run.run_dir, *bench.progress, stop, run_options);
}

}  // namespace

std::vector<std::vector<RunSummary>> RunBenchesConcurrently(const std::vector<BenchPlan>& benches,
                                                            const ExecutorOptions& options,
                                                            const std::atomic<bool>& stop) {
  std::vector<std::vector<RunSummary>> summaries(benches.size());
  std::atomic<bool> stop_all{false};
  std::atomic<size_t> running{benches.size()};
  FirstFailure failure;
  std::vector<std::thread> threads;
  for (size_t b = 0; b < benches.size(); ++b) {
    threads.emplace_back([&, b] {
      const BenchPlan& bench = benches[b];
      for (const BenchSequenceRun& run : bench.runs) {
        try {
          if (stop_all) throw RunInterrupted("stopped before it started");
          summaries[b].push_back(StartOrContinue(bench, run, options, stop_all));
        } catch (...) {
          failure.Record(bench.name + ", run " + run.run_dir.string());
          stop_all = true;
          break;
        }
      }
      --running;
    });
  }
  while (running > 0) {
    if (stop) stop_all = true;
    std::this_thread::sleep_for(kStopPollInterval);
  }
  for (std::thread& t : threads) t.join();
  failure.RethrowIfAny();
  return summaries;
}

}  // namespace adahrs::calib
