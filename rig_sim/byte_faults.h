// Byte-level line faults around any virtual device (a SerialDevice decorator), as a broken cable,
// a noisy line or a hung instrument would show them to the client:
//   "silent"       the device stops answering: nothing reaches it and nothing comes back.
//   "garbage"      the device answers garbage: every byte it sends is replaced by a random byte
//                  (same count, same timing); what it receives is unchanged.
//   "drop_rate"    each byte, either direction, is lost with this probability (0…1).
//   "corrupt_rate" each byte, either direction, has one random bit flipped with this probability.
// Rates are independent per byte (a memoryless line; bursts are left out). Random draws come from
// two streams derived from the seed (client→device and device→client), so the device's output
// faults depend only on the sequence of bytes it sends: the same seed and the same simulated
// timeline give the same faulted stream at any time scale.
// Physical faults and everything else pass through to the wrapped device.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/random.h"
#include "rig_sim/serial_device.h"

namespace adahrs::rig_sim {

struct ByteFaultState {
  bool silent = false;
  bool garbage = false;
  double drop_rate = 0.0;
  double corrupt_rate = 0.0;
};

struct ByteFaultCounters {
  uint64_t bytes_dropped = 0;
  uint64_t bytes_corrupted = 0;
  uint64_t bytes_silenced = 0;  ///< bytes not delivered in either direction while silent
};

class ByteFaultDevice : public SerialDevice {
 public:
  static constexpr const char* kSilent = "silent";
  static constexpr const char* kGarbage = "garbage";
  static constexpr const char* kDropRate = "drop_rate";
  static constexpr const char* kCorruptRate = "corrupt_rate";

  ByteFaultDevice(std::unique_ptr<SerialDevice> inner, uint64_t seed);

  /// The fault names above, on/off faults first.
  static std::vector<std::string> FaultNames();
  /// True for "silent" and "garbage" (on/off), false for the rates.
  static bool IsSwitch(const std::string& fault);
  static bool IsRate(const std::string& fault);

  /// Switches "silent" or "garbage"; throws std::invalid_argument naming the role otherwise.
  void SetSwitch(const std::string& fault, bool on);
  /// Sets "drop_rate" or "corrupt_rate" in [0, 1]; throws std::invalid_argument naming the role,
  /// the fault and the value otherwise.
  void SetRate(const std::string& fault, double rate);

  const ByteFaultState& state() const { return state_; }
  const ByteFaultCounters& counters() const { return counters_; }
  SerialDevice& inner() { return *inner_; }
  const SerialDevice& inner() const { return *inner_; }

  const std::string& role() const override { return inner_->role(); }
  void Receive(std::span<const uint8_t> bytes, double now_s) override;
  void Advance(double now_s, double dt_s, RigEnvironment& env) override;
  void TakeOutput(double now_s, std::vector<uint8_t>& out) override;
  std::vector<std::string> PhysicalFaults() const override { return inner_->PhysicalFaults(); }
  std::string LineReport() const override { return inner_->LineReport(); }
  /// The wrapped unit's count as of the last output that reached the line whole in number of
  /// bytes (not silent, not garbage): packets the client can never read are not counted for it.
  std::optional<uint64_t> DataPacketCount() const override { return packet_count_; }
  void SetPhysicalFault(const std::string& fault, bool on) override {
    inner_->SetPhysicalFault(fault, on);
  }

 private:
  // Applies drop and corrupt to bytes[from, end) in place, using `rng`.
  void ApplyLineNoise(std::vector<uint8_t>& bytes, size_t from, common::Rng& rng);

  std::unique_ptr<SerialDevice> inner_;
  ByteFaultState state_;
  ByteFaultCounters counters_;
  common::Rng to_device_rng_;
  common::Rng to_client_rng_;
  std::vector<uint8_t> in_;
  std::optional<uint64_t> packet_count_;
};

}  // namespace adahrs::rig_sim
