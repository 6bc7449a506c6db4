// Test helper: the virtual rig as a separate process, the way the pipeline meets it in production
// (docs/rig.md). RigProcess starts `$ADAHRS_BIN_DIR/adahrs rig --config <dir>/rig.json
// --manifest <dir>/manifest.json --run-dir <dir> --time-scale K` in a fresh temporary directory,
// waits (bounded) for the manifest, and exposes the port of every role, the truth directory and a
// station file for those ports. The destructor sends SIGTERM, waits for the process and removes
// the directory. Example:
//   adahrs::testing::RigProcess rig(200.0);
//   const hil::Station station = hil::Station::Load(rig.WriteStation());
//   rig.Control("fault imu2 silent on");   // "OK imu2 silent on"
// The station lists every role the rig serves: its instruments (addresses from the rig config),
// its units (baud from the manifest), the rig's site and time scale, and the control port as the
// "virtual_fixture" operator. Control() opens the control port for one command; do not call it
// while an OpenStation()'s operator is mid-command on the same port. The rig's stdout and stderr
// go to <dir>/rig.log, quoted in the error if it fails to start. Header-only; links nothing but
// the standard library, POSIX and nlohmann::json.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

extern char** environ;

namespace adahrs::testing {

/// Wall time allowed for the rig's manifest to appear (a sanitizer build starts slowly).
inline constexpr double kRigStartTimeoutS = 30.0;

class RigProcess {
 public:
  /// Starts the rig at `time_scale` (simulated s per wall s; the top speed in lockstep) with
  /// `config` (the rig's built-in default config when absent).
  explicit RigProcess(double time_scale,
                      std::optional<nlohmann::json> config = std::nullopt,
                      bool lockstep = false)
      : time_scale_(time_scale), lockstep_(lockstep) {
    const char* bin_dir = std::getenv("ADAHRS_BIN_DIR");
    if (bin_dir == nullptr) throw std::runtime_error("RigProcess: ADAHRS_BIN_DIR is not set");
    binary_ = std::filesystem::path(bin_dir) / "adahrs";
    config_ = config ? *std::move(config) : DefaultConfig();
    std::string dir_template =
        (std::filesystem::temp_directory_path() / "adahrs-rig-XXXXXX").string();
    if (::mkdtemp(dir_template.data()) == nullptr) {
      throw std::runtime_error("RigProcess: cannot create a temporary directory");
    }
    dir_ = dir_template;
    std::ofstream(dir_ / "rig.json") << config_.dump(2) << "\n";
    Spawn();
    try {
      WaitForManifest(kRigStartTimeoutS);
    } catch (...) {
      Stop();
      throw;
    }
  }

  ~RigProcess() { Stop(); }

  /// Sends SIGTERM and waits for the rig to exit (its exit report is in rig.log, its packet log
  /// flushed); the directory stays until the destructor.
  void Terminate() { EndProcess(); }

  /// The rig's built-in configuration (`adahrs rig --print-default-config`).
  static nlohmann::json BuiltInConfig() {
    const char* bin_dir = std::getenv("ADAHRS_BIN_DIR");
    if (bin_dir == nullptr) throw std::runtime_error("RigProcess: ADAHRS_BIN_DIR is not set");
    const std::string command =
        (std::filesystem::path(bin_dir) / "adahrs").string() + " rig --print-default-config";
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) throw std::runtime_error("RigProcess: cannot run " + command);
    std::string text;
    char buffer[4096];
    size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) text.append(buffer, n);
    if (::pclose(pipe) != 0) throw std::runtime_error("RigProcess: " + command + " failed");
    return nlohmann::json::parse(text);
  }
  RigProcess(const RigProcess&) = delete;
  RigProcess& operator=(const RigProcess&) = delete;

  /// The run directory (manifest, rig.json, rig.log, ports/, truth/).
  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path truth_dir() const { return dir_ / "truth"; }
  const nlohmann::json& manifest() const { return manifest_; }
  const nlohmann::json& config() const { return config_; }
  double time_scale() const { return time_scale_; }
  pid_t pid() const { return pid_; }

  /// The `ports/<role>` symlink of `role` (throws if the rig has no such role).
  std::string Port(const std::string& role) const {
    if (!manifest_["links"].contains(role)) {
      throw std::runtime_error("RigProcess: the rig has no role " + role);
    }
    return manifest_["links"][role].get<std::string>();
  }

  /// A station (docs/station.md) for every role of this rig, on its ports/ links.
  nlohmann::json StationJson() const {
    const auto port = [](const std::string& path, unsigned baud, const char* flow) {
      return nlohmann::json{{"path", path},
                            {"baud", baud},
                            {"data_bits", 8},
                            {"parity", "N"},
                            {"stop_bits", 1},
                            {"flow", flow}};
    };
    nlohmann::json instruments = nlohmann::json::object();
    for (const nlohmann::json& instrument : manifest_["instruments"]) {
      const std::string role = instrument["role"];
      const std::string kind = instrument["kind"];
      const nlohmann::json& section = config_["instruments"][kind];
      int address = 0;
      unsigned baud = 9600;
      const char* flow = "none";
      if (kind == "watlow_f4") address = section["modbus_address"].get<int>();
      if (kind == "druck_adts_prologix") {
        address = section["gpib_address"].get<int>();
        baud = 115200;
      }
      if (kind == "watlow_942") flow = "xonxoff";
      instruments[role] = {{"type", kind},
                           {"port", port(Port(role), baud, flow)},
                           {"address", address},
                           {"timeout_ms", 1000},
                           {"retries", 2}};
    }
    nlohmann::json units = nlohmann::json::array();
    for (const nlohmann::json& unit : manifest_["units"]) {
      const std::string role = unit["role"];
      units.push_back({{"role", role},
                       {"kind", unit["kind"]},
                       {"slot", unit["slot"]},
                       {"timeout_ms", 500},
                       {"port", port(Port(role), unit["baud"].get<unsigned>(), "none")}});
    }
    nlohmann::json station = {
        {"name", "virtual rig (test)"},
        {"time_scale", time_scale_},
        {"site",
         {{"latitude_deg", manifest_["station"]["latitude_deg"]},
          {"height_m", manifest_["station"]["height_m"]}}},
        {"instruments", instruments},
        {"units", units},
        {"operator",
         {{"type", "virtual_fixture"}, {"port", port(Port("control"), 115200, "none")}}}};
    if (lockstep_) station["clock_file"] = manifest_["clock"]["file"];
    return station;
  }

  /// Writes StationJson() (changed by `edit`, if given) to <dir>/<file_name>; returns its path.
  std::string WriteStation(const std::string& file_name = "station.json",
                           const std::function<void(nlohmann::json&)>& edit = nullptr) const {
    nlohmann::json station = StationJson();
    if (edit) edit(station);
    const std::filesystem::path path = dir_ / file_name;
    std::ofstream(path) << station.dump(2) << "\n";
    return path.string();
  }

  /// Sends one line on the rig's control port and returns the reply line ("OK …" / "ERR …").
  std::string Control(const std::string& line) const {
    const std::string path = Port("control");
    const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY);
    if (fd < 0) throw std::runtime_error("RigProcess: cannot open " + path);
    termios tio{};
    ::tcgetattr(fd, &tio);
    ::cfmakeraw(&tio);
    ::tcsetattr(fd, TCSANOW, &tio);
    ::tcflush(fd, TCIFLUSH);
    const std::string out = line + "\n";
    const bool written = ::write(fd, out.data(), out.size()) == static_cast<ssize_t>(out.size());
    std::string reply;
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (written && std::chrono::steady_clock::now() < end) {
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, 10) <= 0) continue;
      char c = 0;
      if (::read(fd, &c, 1) != 1) continue;
      if (c == '\n') break;
      if (c != '\r') reply += c;
    }
    ::close(fd);
    if (!written) throw std::runtime_error("RigProcess: cannot write to " + path);
    return reply;
  }

 private:
  // Ends the process (EndProcess) and removes the directory.
  void Stop() {
    EndProcess();
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }

  // SIGTERM, then SIGKILL if the rig has not exited within 10 s.
  void EndProcess() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      int status = 0;
      const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (::waitpid(pid_, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > end) {
          ::kill(pid_, SIGKILL);
          ::waitpid(pid_, &status, 0);
          break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    }
    pid_ = -1;
  }

  nlohmann::json DefaultConfig() const { return BuiltInConfig(); }

  void Spawn() {
    const std::string log = (dir_ / "rig.log").string();
    std::vector<std::string> args = {binary_.string(),
                                     "rig",
                                     "--config",
                                     (dir_ / "rig.json").string(),
                                     "--manifest",
                                     (dir_ / "manifest.json").string(),
                                     "--run-dir",
                                     dir_.string(),
                                     "--time-scale",
                                     std::to_string(time_scale_)};
    if (lockstep_) args.push_back("--lockstep");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(
        &actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    const int rc = posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) {
      pid_ = -1;
      throw std::runtime_error("RigProcess: cannot start " + binary_.string());
    }
  }

  void WaitForManifest(double timeout_s) {
    const std::filesystem::path path = dir_ / "manifest.json";
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!std::filesystem::exists(path)) {
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        throw std::runtime_error("RigProcess: the rig exited before writing its manifest: " +
                                 Log());
      }
      if (std::chrono::steady_clock::now() > end) {
        throw std::runtime_error("RigProcess: no manifest within " + std::to_string(timeout_s) +
                                 " s: " + Log());
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    std::ifstream in(path);
    manifest_ = nlohmann::json::parse(in);
  }

  std::string Log() const {
    std::ifstream in(dir_ / "rig.log");
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

  double time_scale_;
  bool lockstep_;
  std::filesystem::path binary_;
  std::filesystem::path dir_;
  nlohmann::json config_;
  nlohmann::json manifest_;
  pid_t pid_ = -1;
};

}  // namespace adahrs::testing
