#include "calib/campaign/bench_runs.h"

#include <chrono>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

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
          NewRunOptions run_options;
          run_options.station_file = bench.station_file;
          run_options.sequence_file = run.sequence_file;
          run_options.run_dir = run.run_dir;
          run_options.executor = options;
          summaries[b].push_back(StartRun(run_options, *bench.progress, stop_all));
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
