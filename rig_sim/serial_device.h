// A virtual device behind one serial port of the rig: an instrument or a unit.
//
// The rig advances simulated time in fixed world frames (10 ms). Each frame, in a fixed order,
// it hands every device the bytes its client sent since the last frame (Receive), advances the
// device's physics by one frame (Advance, reading and writing the shared RigEnvironment), and takes
// the bytes the device has released for its client by that time (TakeOutput). The same simulated
// timeline results at any time scale: wall time only decides how fast frames are taken.
// The device never touches a file descriptor; transports (hil/) move the bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "rig_sim/rig_environment.h"

namespace adahrs::rig_sim {

class SerialDevice {
 public:
  virtual ~SerialDevice() = default;

  /// The role this device plays in the manifest ("rate_table", "chamber", "imu1", …).
  virtual const std::string& role() const = 0;

  /// Bytes that arrived from the client, at simulated time `now_s`.
  virtual void Receive(std::span<const uint8_t> bytes, double now_s) = 0;

  /// Advances the device's physics and timers by `dt_s` to `now_s`.
  virtual void Advance(double now_s, double dt_s, RigEnvironment& env) = 0;

  /// Appends to `out` the bytes released for the client by `now_s`.
  virtual void TakeOutput(double now_s, std::vector<uint8_t>& out) = 0;

  /// The device's physical fault modes (e.g. "cannot_reach_set_point", "never_stable");
  /// byte-level faults (silence, garbage, dropped or corrupted bytes) are applied by the rig
  /// around any device and are not listed here.
  virtual std::vector<std::string> PhysicalFaults() const { return {}; }

  /// Switches a physical fault on or off; throws std::invalid_argument naming the device and
  /// the fault when the device has no such fault.
  virtual void SetPhysicalFault(const std::string& fault, bool on);

  /// What the device itself sent, dropped or refused on its line, as "name=value" words for the
  /// rig's exit report (e.g. a unit's data packets refused by its full transmit buffer); empty
  /// when the device keeps no such counts.
  virtual std::string LineReport() const { return ""; }

  /// A unit's data packets queued for its client, counted on the unit's 8-bit packet counter
  /// unwrapped (the last packet's index + 1; hil/rig_port_counts.h); nullopt for a device that
  /// sends no counted packets.
  virtual std::optional<uint64_t> DataPacketCount() const { return std::nullopt; }

  /// The GPIB address a client must address behind this port (a GPIB adapter's instrument), for
  /// the manifest; nullopt for a device on the serial line itself.
  virtual std::optional<int> GpibAddress() const { return std::nullopt; }
};

inline void SerialDevice::SetPhysicalFault(const std::string& fault, bool) {
  throw std::invalid_argument(role() + ": no physical fault named '" + fault + "'");
}

}  // namespace adahrs::rig_sim
