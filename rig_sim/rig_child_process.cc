#include "rig_sim/rig_child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

extern char** environ;

namespace adahrs::rig_sim {
namespace {

// The last lines of the rig's log are what explains a failed start.
constexpr size_t kLogTailChars = 2000;

std::string DescribeStatus(int status) {
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  return "stopped (wait status " + std::to_string(status) + ")";
}

}  // namespace

RigChildProcess::RigChildProcess(RigChildOptions options) : options_(std::move(options)) {
  std::filesystem::create_directories(options_.run_dir);
  Spawn();
  try {
    WaitForManifest();
  } catch (...) {
    Stop();
    throw;
  }
}

RigChildProcess::~RigChildProcess() { Stop(); }

void RigChildProcess::Spawn() {
  std::vector<std::string> args = {options_.binary.string(),
                                   "rig",
                                   "--config",
                                   options_.config_file.string(),
                                   "--manifest",
                                   (options_.run_dir / "manifest.json").string(),
                                   "--run-dir",
                                   options_.run_dir.string(),
                                   "--time-scale",
                                   std::to_string(options_.time_scale)};
  if (options_.lockstep) args.push_back("--lockstep");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string log = log_file().string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(
      &actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  const int rc = posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    pid_ = -1;
    throw RigProcessError("cannot start the rig " + options_.binary.string() + ": " +
                          std::strerror(rc));
  }
}

namespace {

// True when `path` holds the manifest of the rig process `pid` (written atomically, so a file
// that exists is whole).
bool ManifestOf(const std::filesystem::path& path, pid_t pid) {
  std::ifstream in(path);
  if (!in) return false;
  const nlohmann::json manifest = nlohmann::json::parse(in, nullptr, false);
  return manifest.is_object() && manifest.value("pid", int64_t{-1}) == static_cast<int64_t>(pid);
}

}  // namespace

void RigChildProcess::WaitForManifest() {
  // The rig writes the manifest atomically (temporary file + rename) once every port is open; one
  // holding another pid is a dead rig's, which this rig removes before writing its own.
  const std::filesystem::path path = options_.run_dir / "manifest.json";
  const auto end =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(options_.start_timeout_s);
  while (!ManifestOf(path, pid_)) {
    if (const std::optional<std::string> exit = ExitDescription()) {
      throw RigProcessError("the rig " + *exit + " before writing its manifest " + path.string());
    }
    if (std::chrono::steady_clock::now() > end) {
      throw RigProcessError("the rig wrote no manifest (" + path.string() + ") within " +
                            std::to_string(options_.start_timeout_s) + " s; " +
                            log_file().string() + " ends: " + LogTail());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::ifstream in(path);
  manifest_ = nlohmann::json::parse(in);
}

std::optional<std::string> RigChildProcess::ExitDescription() {
  if (pid_ > 0) {
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      exit_description_ =
          DescribeStatus(status) + "; " + log_file().string() + " ends: " + LogTail();
    }
  }
  return exit_description_;
}

void RigChildProcess::Stop() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGTERM);
  int status = 0;
  const auto end =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(kRigStopTimeoutS);
  while (::waitpid(pid_, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > end) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  pid_ = -1;
  exit_description_ = "stopped (" + DescribeStatus(status) + ")";
}

std::string RigChildProcess::LogTail() const {
  std::ifstream in(log_file());
  std::stringstream text;
  text << in.rdbuf();
  const std::string all = text.str();
  return all.size() > kLogTailChars ? "..." + all.substr(all.size() - kLogTailChars) : all;
}

}  // namespace adahrs::rig_sim
