// The virtual lab as one object: every configured instrument and unit on its own pseudo-terminal,
// each behind a byte-fault wrapper (byte_faults.h), plus the control port (control_port.h), served
// by a DeviceHost on the time-scaled clock.
//
// Frame order: instruments first (they write the shared RigEnvironment: chamber air, table rate,
// pressures), then the IMU and ADS units (they read it), then the control port. Roles: each
// instrument's own role, "imu1"…"imu4", "ads1"…, "control".
// Files in the run directory:
//   truth/<serial>.json   every simulated unit's drawn parameters (written when the rig is built)
//   packets/<role>.txt    with the config's packet_log: every packet each unit sent
//                         (UnitDevice::SetPacketLog)
//   ports/<role>          symlink to the role's slave device (stable names for station files)
// and the manifest (role → slave path, links, units, instruments; docs/rig.md "Manifest"),
// written atomically (temporary file + rename) once every port is open and the clock runs, and
// removed with the links when the rig stops (ClaimManifestPath clears what a dead rig left).
#pragma once

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rig_sim/byte_faults.h"
#include "rig_sim/control_port.h"
#include "rig_sim/device_host.h"
#include "rig_sim/rig_config.h"
#include "rig_sim/unit_device.h"

namespace adahrs::rig_sim {

/// Version of the manifest layout (docs/rig.md).
inline constexpr int kManifestVersion = 1;
/// The clock file (hil/rig_clock.h) in the run directory; the manifest's "clock" names it.
inline constexpr const char* kClockFileName = "clock";

/// Makes `manifest_path` free for a new rig, before it starts: a manifest left by a rig whose
/// process no longer runs (or one that cannot be read) is removed with the port links it lists;
/// one whose process still runs is refused with std::runtime_error naming the path and pid.
/// Returns a line for the log, empty when there was no manifest.
std::string ClaimManifestPath(const std::filesystem::path& manifest_path);

class Rig {
 public:
  /// Builds every device, opens the ptys and writes truth/ into `run_dir` (created if needed).
  /// Throws common::ParamError naming the config's JSON path for an unknown role or fault in
  /// the start faults, std::runtime_error for files that cannot be written.
  Rig(const RigConfig& config, const std::filesystem::path& run_dir);
  ~Rig();
  Rig(const Rig&) = delete;
  Rig& operator=(const Rig&) = delete;

  /// Starts the clock, creates ports/<role> symlinks and writes the manifest to `manifest_path`.
  void Start(const std::filesystem::path& manifest_path);
  /// Stops the clock and removes the manifest and the port links Start wrote, so nobody waiting
  /// for a manifest can take a stopped rig's ports (idempotent); the ptys close when the Rig is
  /// destroyed.
  void Stop();

  /// Executes a control command as the control port would, on the frame thread.
  std::string Control(const std::string& command);

  /// Role → slave device path, including "control".
  const std::map<std::string, std::string>& ports() const { return ports_; }
  /// The manifest as written by Start().
  nlohmann::json Manifest() const;
  DeviceHost& host() { return *host_; }
  const std::filesystem::path& run_dir() const { return run_dir_; }

 private:
  void AddDevice(std::unique_ptr<SerialDevice> device,
                 const std::string& kind,
                 int imu_slot,
                 uint64_t fault_seed);
  // Opens packets/<role>.txt for a unit when the config asks for the packet log.
  void LogPackets(UnitDevice& device);
  void WriteLinks() const;
  void RemoveManifestAndLinks();

  RigConfig config_;
  std::filesystem::path run_dir_;
  std::filesystem::path manifest_path_;  ///< written by Start, removed by Stop
  std::unique_ptr<DeviceHost> host_;
  std::unique_ptr<RigControl> control_;
  std::vector<std::unique_ptr<std::ofstream>> packet_logs_;  ///< written on the frame thread
  std::vector<ControlTarget> targets_;
  std::map<std::string, std::string> ports_;
  nlohmann::json units_ = nlohmann::json::array();
  nlohmann::json instruments_ = nlohmann::json::array();
};

}  // namespace adahrs::rig_sim
