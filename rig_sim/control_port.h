// The rig's control port: a line protocol on its own pseudo-terminal (role "control") through
// which a test or an operator switches faults, moves the virtual fixture and reads the clock.
// One command per line (LF or CR LF), one reply line each: "OK ..." or "ERR <reason>":
//   time                                   OK <simulated seconds>
//   status                                 OK time_s=... time_scale=... roles=a,b,...
//                                          faults=role:fault=value,...
//   env                                    OK the shared physical state (chamber air, table,
//                                          pressures)
//   faults <role>                          OK the fault names the role accepts
//   fault <role> <fault> on|off            byte faults silent, garbage; the device's physical
//                                          faults
//   fault <role> drop_rate|corrupt_rate <0...1>
//   orientation <imu role> [code]          set (11 12 21 22 31 32) or read the unit's fixture code
//   help                                   OK the command list
// Commands run on the rig's frame thread between device frames, so they take effect at a frame
// boundary of the simulated clock (the command's own frame, after the devices before it).
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "rig_sim/byte_faults.h"
#include "rig_sim/serial_device.h"

namespace adahrs::rig_sim {

/// A device the control port can reach.
struct ControlTarget {
  std::string role;
  ByteFaultDevice* device = nullptr;  ///< the device with its byte-fault wrapper (not owned)
  int imu_slot = -1;                  ///< RigEnvironment::imu_orientation index, or -1
};

class RigControl {
 public:
  RigControl(std::vector<ControlTarget> targets, double time_scale);

  /// Executes one command line at simulated time `now_s`; returns the reply without newline.
  std::string Execute(std::string_view line, double now_s, RigEnvironment& env);

  /// Switches `fault` of `role`: `value` is "on"/"off" or a rate. Throws std::invalid_argument
  /// naming the role, the fault and the value when any of them is not accepted.
  void SetFault(const std::string& role, const std::string& fault, const std::string& value);

 private:
  const ControlTarget& Target(const std::string& role) const;
  std::string Status(double now_s) const;

  std::vector<ControlTarget> targets_;
  double time_scale_;
  std::map<std::string, std::string> active_faults_;  // "role:fault" → value, for status
};

/// The control port as a SerialDevice (role "control"): lines in, replies out at the frame.
class ControlPortDevice : public SerialDevice {
 public:
  /// Longest accepted command line; a longer one is answered "ERR line too long".
  static constexpr size_t kMaxLineBytes = 256;

  explicit ControlPortDevice(RigControl* control) : control_(control) {}

  const std::string& role() const override { return role_; }
  void Receive(std::span<const uint8_t> bytes, double now_s) override;
  void Advance(double now_s, double dt_s, RigEnvironment& env) override;
  void TakeOutput(double now_s, std::vector<uint8_t>& out) override;

 private:
  RigControl* control_;
  std::string role_ = "control";
  std::string partial_;
  bool overlong_ = false;
  std::vector<std::string> lines_;
  std::string replies_;
};

}  // namespace adahrs::rig_sim
