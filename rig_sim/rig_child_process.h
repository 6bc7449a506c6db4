// The virtual rig as a child process, for jobs that run the pipeline against it (`adahrs demo`):
// starts `<binary> rig --config <config> --manifest <run_dir>/manifest.json --run-dir <run_dir>
// --time-scale K` (the rig command, docs/rig.md) with its stdout and stderr in <run_dir>/rig.log,
// waits a bounded wall time for the manifest (the rig writes it once every port is open), and
// always stops it: Stop() and the destructor send SIGTERM and wait, SIGKILL after
// kRigStopTimeoutS. The pipeline meets the rig only through its ports, as it would a real lab.
// Errors: RigProcessError quoting the end of rig.log when the rig cannot start, exits before its
// manifest, or does not write it in time.
// Left out: restarting a rig that died (ExitDescription() says that it did; the caller decides).
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace adahrs::rig_sim {

class RigProcessError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Wall seconds the rig has to exit after SIGTERM before it is killed.
inline constexpr double kRigStopTimeoutS = 10.0;

struct RigChildOptions {
  std::filesystem::path binary;       ///< the adahrs binary (e.g. /proc/self/exe)
  std::filesystem::path run_dir;      ///< manifest.json, rig.log, ports/, truth/ go here
  std::filesystem::path config_file;  ///< rig config (docs/rig.md "Configuration")
  double time_scale = 1.0;            ///< simulated s per wall s (the top speed in lockstep)
  double start_timeout_s = 30.0;      ///< wall s allowed for the manifest to appear
  bool lockstep = false;              ///< the rig's clock waits for slow readers
};

class RigChildProcess {
 public:
  /// Starts the rig and waits for its manifest; throws RigProcessError (the rig stopped).
  explicit RigChildProcess(RigChildOptions options);
  ~RigChildProcess();
  RigChildProcess(const RigChildProcess&) = delete;
  RigChildProcess& operator=(const RigChildProcess&) = delete;

  /// SIGTERM and wait (SIGKILL after kRigStopTimeoutS); idempotent.
  void Stop();
  /// Empty while the rig runs; how it ended ("exited with status 1", "killed by signal 9") once
  /// it has, with the end of rig.log.
  std::optional<std::string> ExitDescription();

  const nlohmann::json& manifest() const { return manifest_; }
  const std::filesystem::path& run_dir() const { return options_.run_dir; }
  std::filesystem::path truth_dir() const { return options_.run_dir / "truth"; }
  std::filesystem::path log_file() const { return options_.run_dir / "rig.log"; }
  pid_t pid() const { return pid_; }

 private:
  void Spawn();
  void WaitForManifest();
  std::string LogTail() const;

  RigChildOptions options_;
  nlohmann::json manifest_;
  pid_t pid_ = -1;
  std::optional<std::string> exit_description_;
};

}  // namespace adahrs::rig_sim
