// The virtual rate table on the rig's serial port: an Aero 8xx controller speaking ATL
// (hil/codecs/atl_codec.h, command table rig_sim/data/atl_commands.json) in front of the table
// physics (rig_sim/rate_table.h). Writes env.table_rate_dps and env.table_angle_deg (the true
// platter motion, ripple included) every world frame. A line runs at the 1 ms physics tick at or
// before its arrival, its reply leaves after reply_latency_s at 9600 8N1 (1.04 ms per byte).
// Refusals (reply texts UNKNOWN, templates in the command table) are never clamped: unknown
// mnemonic or form, bad argument, beyond the table's or the drive's limits (max_rate_dps,
// max_accel_dps2), motion with the servo off, motion or servo-on with the interlock open.
// Physical faults: "interlock_open" (the door/e-stop input), "stalled" (platter jammed).
// Units: deg/s, deg/s^2, deg; simulated seconds.
// Timing, refusals, faults: docs/rig/rate-table.md ("Refusals", "Faults", the device's timing).
// Left out: echo of received characters (UNKNOWN on the real unit), XON/XOFF flow control, input
// overrun (the pty never overruns), a power-on banner; byte-level faults belong to the rig.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/param_reader.h"
#include "hil/codecs/atl_codec.h"
#include "hil/codecs/atl_command_table.h"
#include "rig_sim/rate_table.h"
#include "rig_sim/serial_device.h"

namespace adahrs::rig_sim {

struct RateTableDeviceConfig {
  std::string role = "rate_table";
  double baud = 9600.0;            ///< 8N1: 10 bits per byte on the line
  double reply_latency_s = 0.002;  ///< controller time from end of line to first reply byte (E)
  double initial_angle_deg = 0.0;
  RateTableParams physics;
};

class RateTableDevice : public SerialDevice {
 public:
  /// Throws common::ParamError naming the command table's source when the table binds an
  /// operation this controller does not have, or gives a form an argument or a reply the
  /// operation cannot take.
  RateTableDevice(const RateTableDeviceConfig& config,
                  hil::AtlCommandTable commands,
                  const std::string& commands_source);

  const std::string& role() const override { return config_.role; }
  void Receive(std::span<const uint8_t> bytes, double now_s) override;
  void Advance(double now_s, double dt_s, RigEnvironment& env) override;
  void TakeOutput(double now_s, std::vector<uint8_t>& out) override;
  std::vector<std::string> PhysicalFaults() const override;
  void SetPhysicalFault(const std::string& fault, bool on) override;

  /// The door/e-stop interlock input (same as the "interlock_open" fault).
  void SetInterlockOpen(bool open) { table_.SetInterlockOpen(open); }

  const RateTable& table() const { return table_; }
  const hil::AtlCommandTable& commands() const { return commands_; }

 private:
  struct PendingLine {
    hil::AtlLine line;
    double received_s;
  };
  void Execute(const hil::AtlLine& line, double at_s);
  // The reply data for a parsed, well-formed command (an error text when the table refuses it).
  std::string Perform(const hil::AtlParsed& parsed, const std::string& line_text);
  double Value(const std::string& operation, const std::string& mnemonic) const;
  // The limits the controller enforces for a command: the table's, narrowed by the drive's
  // configured limits for rate and acceleration; nullopt when the form takes no number.
  std::optional<std::pair<double, double>> EnforcedLimits(const hil::AtlParsed& parsed) const;
  // The refusal of SGO: the sine's peak rate or acceleration beyond the drive's limit, or a sine
  // that cannot run (amplitude < 0, frequency or cycles <= 0).
  std::string SineRefusal(const hil::AtlParsed& parsed, const std::string& line_text) const;
  void Send(std::string_view bytes, double ready_s);

  RateTableDeviceConfig config_;
  hil::AtlCommandTable commands_;
  hil::AtlLineFramer framer_;
  RateTable table_;
  double byte_time_s_;
  std::deque<PendingLine> pending_;
  std::deque<std::pair<double, uint8_t>> output_;  // (release time, byte)
  double line_free_s_ = 0.0;                       // when the transmitter is next idle
  std::map<std::string, double> settings_;         // stored values of "setting" commands
  double sine_amplitude_deg_ = 0.0;
  double sine_frequency_hz_ = 1.0;
  double sine_cycles_ = 1.0;
};

/// The path of the default command table (rig_sim/data/atl_commands.json in the source tree).
std::string DefaultAtlCommandTablePath();

/// Builds the device from the rig config's rate-table section (every key required and checked;
/// see docs/rig/rate-table.md). A relative `command_table` path is taken relative to the config
/// file's folder.
std::unique_ptr<SerialDevice> MakeRateTableDevice(const common::ParamReader& config);

/// A complete default section for MakeRateTableDevice.
nlohmann::json DefaultRateTableConfig();

}  // namespace adahrs::rig_sim
