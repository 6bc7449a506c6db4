// adahrs run: runs a calibration sequence on a station (docs/executor.md), or resumes an
// interrupted run. Thin: parses, installs the handler of SIGINT, SIGTERM and SIGHUP (a stop
// request the executor polls: the rig is left safe and the run resumable, exit status 128 + the
// signal's number: 130, 143, 129), prints progress lines.
//   adahrs run --station FILE --sequence FILE --run-dir DIR
//   adahrs run --resume DIR

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "apps/commands.h"
#include "apps/stop_signals.h"
#include "calib/executor/run_session.h"

namespace adahrs::apps {
namespace {

class ConsoleProgress : public calib::ProgressSink {
 public:
  void Report(const calib::ProgressReport& r) override {
    std::string units;
    for (const calib::UnitProgress& u : r.units) {
      units += fmt::format(" {}:{}/{}{}",
                           u.role,
                           u.packets,
                           u.acquired,
                           u.lost > 0 ? fmt::format(" lost {}", u.lost) : "");
    }
    std::cout << fmt::format("t={:.1f}s step {}/{} {} | {} | ETA {:.0f} s |{}\n",
                             r.t_s,
                             r.step + 1,
                             r.step_count,
                             r.step_kind,
                             r.action_text,
                             r.eta_s,
                             units);
  }
  void Note(const std::string& text) override { std::cout << "note: " << text << "\n"; }
};

struct RunArgs {
  std::string station;
  std::string sequence;
  std::string run_dir;
  std::string resume;
  bool plain_csv = false;
};

int RunAndReport(const RunArgs& a) {
  const std::atomic<bool>& stop = InstallStopSignals();
  ConsoleProgress progress;
  const std::string dir = a.resume.empty() ? a.run_dir : a.resume;
  calib::NewRunOptions options;
  options.station_file = a.station;
  options.sequence_file = a.sequence;
  options.run_dir = a.run_dir;
  if (a.plain_csv) options.storage = hil::RecordingStorage::kPlainCsv;
  try {
    const calib::RunSummary summary = a.resume.empty() ? calib::StartRun(options, progress, stop)
                                                       : calib::ResumeRun(a.resume, progress, stop);
    std::cout << fmt::format("run {}: {}; {} rows recorded, {} packets lost\n",
                             summary.run_dir.string(),
                             summary.status,
                             summary.rows,
                             summary.lost);
    return 0;
  } catch (const calib::RunInterrupted& e) {
    std::cerr << fmt::format(
        "adahrs run: interrupted by {} ({}); the rig is safe. Resume with: "
        "adahrs run --resume {}\n",
        StopSignalName(),
        e.what(),
        dir);
    return StopExitStatus();
  } catch (const calib::RunError& e) {
    std::cerr << "adahrs run: aborted: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

void RegisterRunCommand(CLI::App& app) {
  CLI::App* run =
      app.add_subcommand("run", "Run a calibration sequence on a station, or resume one");
  auto args = std::make_shared<RunArgs>();
  auto* station = run->add_option("--station", args->station, "Station file (docs/station.md)");
  auto* sequence =
      run->add_option("--sequence", args->sequence, "Sequence file (docs/sequences.md)");
  auto* run_dir = run->add_option("--run-dir", args->run_dir, "Run directory to create");
  auto* resume = run->add_option("--resume", args->resume, "Resume the run in this directory");
  auto* plain_csv = run->add_flag(
      "--plain-csv", args->plain_csv, "Record imu.csv and ads.csv uncompressed (default: .csv.gz)");
  resume->excludes(station)->excludes(sequence)->excludes(run_dir)->excludes(plain_csv);
  run->callback([args] {
    if (args->resume.empty() &&
        (args->station.empty() || args->sequence.empty() || args->run_dir.empty())) {
      throw CLI::ValidationError(
          "run", "--station, --sequence and --run-dir are required (or --resume DIR)");
    }
    const int status = RunAndReport(*args);
    if (status != 0) std::exit(status);
  });
}

}  // namespace adahrs::apps
