// What an IMU and an ADS unit have in common behind their serial port: the firmware's maintenance
// port (firmware_model MaintenanceHandler with its emulated flash), the 100 Hz acquisition clock,
// the paced transmit line, and the unit's physical faults. Subclasses supply one acquisition: read
// the rig's world, step the unit's physics, compensate and encode one data packet. Sample k is
// taken at k · 10 ms and its packet reaches the client when its last byte has left; a maintenance
// response queues behind whatever the line is sending. A full transmit buffer drops whole packets
// (sequence gaps). Physical faults: "unplugged" (no bytes either way, the unit keeps running) and
// "reset" (held unpowered; off is a power-on as RESET does).
// Units: simulated seconds; line rate in baud (8N1).
// Timing, faults and stimulus: docs/rig.md ("Units on their ports", "Faults").
// Left out: the firmware's UART receive overrun, the power-up delay before the first packet,
// physics while unpowered (the sensors keep their thermal state and self-heating).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "firmware_model/unit_firmware.h"
#include "rig_sim/paced_line.h"
#include "rig_sim/serial_device.h"

namespace adahrs::rig_sim {

/// Firmware version every simulated unit reports in IDENTIFY.
inline constexpr uint8_t kSimulatedFirmwareMajor = 1;
inline constexpr uint8_t kSimulatedFirmwareMinor = 0;
inline constexpr uint8_t kSimulatedFirmwarePatch = 0;
/// The firmware's transmit buffer (assumed: the real size is not documented); holds a maximum
/// maintenance response (258 bytes) beside a compensated IMU packet (89 bytes).
inline constexpr size_t kUnitTxBufferBytes = 512;
/// Acquisition period of both unit kinds (docs/unit-protocol.md: 100 Hz).
inline constexpr double kUnitSamplePeriod_s = 0.01;

/// Counters of one unit port (simulator diagnostics; a real unit reports only READ_COUNTERS).
struct UnitPortCounters {
  uint64_t packets_sent = 0;     ///< data packets queued on the line
  uint64_t packets_dropped = 0;  ///< data packets refused by a full transmit buffer
  uint64_t responses_sent = 0;   ///< maintenance responses queued
};

class UnitDevice : public SerialDevice {
 public:
  static constexpr const char* kUnplugged = "unplugged";
  static constexpr const char* kReset = "reset";

  const std::string& role() const override { return role_; }
  void Receive(std::span<const uint8_t> bytes, double now_s) override;
  void Advance(double now_s, double dt_s, RigEnvironment& env) override;
  void TakeOutput(double now_s, std::vector<uint8_t>& out) override;
  std::string LineReport() const override;
  std::vector<std::string> PhysicalFaults() const override { return {kUnplugged, kReset}; }
  void SetPhysicalFault(const std::string& fault, bool on) override;

  const firmware_model::MaintenanceHandler& handler() const { return handler_; }
  const UnitPortCounters& counters() const { return counters_; }
  bool unplugged() const { return unplugged_; }
  bool powered() const { return powered_; }
  int baud() const { return line_.baud(); }
  std::optional<uint64_t> DataPacketCount() const override { return packet_count_; }
  /// Writes a line per data packet queued from now on to `log` (nullptr: off): the sample index
  /// since the rig started, the packet's sequence counter and its first 8 payload bytes in hex
  /// (IMU: az1_t1 az1_t2 ax1_t1 ax1_t2; ADS: ps_cnt pt_cnt, little-endian), so a recording's rows
  /// can be matched to the samples the unit took (simulator truth, docs/rig.md "Run directory").
  void SetPacketLog(std::ostream* log) { packet_log_ = log; }

 protected:
  UnitDevice(std::string role, const firmware_model::UnitIdentity& identity, int baud);

  /// Steps the unit's physics one sample at `sample_s` in `env`; if `encode`, writes the data
  /// packet (handler's mode, constants, sequence and TAG) into `frame` and returns its length.
  virtual uint16_t Acquire(double sample_s,
                           const RigEnvironment& env,
                           bool encode,
                           firmware_model::MaintenanceHandler& handler,
                           uint8_t* frame,
                           uint16_t capacity) = 0;

 private:
  std::string role_;
  firmware_model::FlashStore flash_;
  firmware_model::MaintenanceHandler handler_;
  PacedLine line_;
  uint64_t samples_done_ = 0;
  // The packet counter unwrapped: the last encoded packet's index (steps of the 8-bit counter,
  // whatever became of the packets), and that + 1 of the last one queued for a plugged line.
  std::optional<uint64_t> last_index_;
  std::ostream* packet_log_ = nullptr;
  void LogPacket(uint16_t length);
  uint64_t packet_count_ = 0;
  double last_now_s_ = 0.0;
  bool unplugged_ = false;
  bool powered_ = true;
  UnitPortCounters counters_;
  std::array<uint8_t, firmware_model::kMaxFrameBytes> frame_{};
};

}  // namespace adahrs::rig_sim
