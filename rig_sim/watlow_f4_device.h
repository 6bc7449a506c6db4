// The IMU thermal chamber behind a Watlow F4 controller, as a virtual serial device speaking
// Modbus RTU (hil/codecs/modbus_rtu.h) on the simulated clock. A request is complete when its
// length (from its function code) has arrived; a bad CRC is ignored without a reply until the line
// falls silent; a partial frame is abandoned after partial_frame_timeout_s (the rig notices client
// bytes only at 10 ms world frames). Replies start 3.5 character times plus reply_latency_s after
// the request and leave at the line rate. Every control_tick_s the controller (watlow_f4.h) gets
// the air temperature as its process value and the air (chamber_air.h) steps toward the working set
// point; with control off it relaxes to ambient_c. Fault "cannot_reach_set_point": the capacity
// falls to capacity_ratio_in_fault of nominal while the controller keeps reporting the set point.
// Units: 8N1 at `baud`; °C; simulated seconds; writes RigEnvironment::imu_chamber_air_c.
// Link, timing, physics and faults: docs/rig/watlow-f4.md ("Link", "Physics and faults").
// Left out: the process-value sensor's lag and error, humidity, load, RS-485 bus contention and
// echo, parity other than none.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/param_reader.h"
#include "rig_sim/chamber_air.h"
#include "rig_sim/serial_device.h"
#include "rig_sim/watlow_f4.h"

namespace adahrs::rig_sim {

struct WatlowF4DeviceConfig {
  std::string role = "imu_chamber";
  uint8_t modbus_address = 1;
  int baud = 9600;
  double reply_latency_s = 0.005;         ///< controller turnaround beyond 3.5 characters (UNKNOWN)
  double partial_frame_timeout_s = 0.05;  ///< silence that abandons a partial frame
  double control_tick_s = 0.1;            ///< controller scan and physics step
  WatlowF4Settings controller;
  ChamberAirParams chamber;
  double initial_air_c = 25.0;
  double ambient_c = 23.0;                ///< lab air the chamber drifts to with control off
  double control_off_tau_s = 1800.0;      ///< passive drift time constant with control off
  double capacity_ratio_in_fault = 0.05;  ///< heating/cooling capacity left in the fault
};

class WatlowF4Device : public SerialDevice {
 public:
  /// Fault name for SetPhysicalFault.
  static constexpr const char* kCannotReachSetPoint = "cannot_reach_set_point";

  explicit WatlowF4Device(const WatlowF4DeviceConfig& config);

  const std::string& role() const override { return config_.role; }
  void Receive(std::span<const uint8_t> bytes, double now_s) override;
  void Advance(double now_s, double dt_s, RigEnvironment& env) override;
  void TakeOutput(double now_s, std::vector<uint8_t>& out) override;
  std::vector<std::string> PhysicalFaults() const override { return {kCannotReachSetPoint}; }
  void SetPhysicalFault(const std::string& fault, bool on) override;

  /// The chamber air temperature now (simulator truth).
  double air_c() const { return air_c_; }
  /// The controller (for inspection by tests and the rig's control port).
  const WatlowF4& controller() const { return controller_; }

 private:
  void EndFrameOnSilence(double now_s);
  void ParseBuffer(double now_s);
  void Serve(const hil::modbus::Request& request, double now_s);
  void Reply(const hil::modbus::Response& response, double now_s);
  ChamberAirParams ActiveChamberParams() const;

  WatlowF4DeviceConfig config_;
  WatlowF4 controller_;
  ChamberAir chamber_;
  double air_c_;
  bool chamber_driven_ = true;  // false while the controller's output is off
  bool fault_cannot_reach_ = false;
  int64_t ticks_done_ = 0;

  std::vector<uint8_t> rx_;
  double last_rx_s_ = 0.0;
  bool discarding_ = false;  // after a bad frame: ignore bytes until the line is silent
  std::deque<std::pair<double, uint8_t>> tx_;  // (simulated time the byte is complete, byte)
  double tx_free_s_ = 0.0;
};

/// The rig's factory: reads the chamber's section of the rig config (keys as in
/// DefaultWatlowF4Config(), every one required and range-checked; ParamError names the path).
std::unique_ptr<SerialDevice> MakeWatlowF4Device(const common::ParamReader& config);

/// Parses a config section into the device's settings (used by MakeWatlowF4Device).
WatlowF4DeviceConfig ReadWatlowF4DeviceConfig(const common::ParamReader& config);

/// A complete default section (documented in docs/rig/watlow-f4.md).
nlohmann::json DefaultWatlowF4Config();

}  // namespace adahrs::rig_sim
