#include "rig_sim/unit_device.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

namespace adahrs::rig_sim {

namespace fm = firmware_model;

namespace {

// True if `frame` is the ACK of a RESET request (docs/unit-protocol.md §2 offsets, §6.1 payload).
bool IsResetAck(const uint8_t* frame, uint16_t length) {
  return length >= fm::kFrameHeaderBytes + 2 &&
         frame[3] == static_cast<uint8_t>(fm::PacketType::kMaintenanceResponse) &&
         frame[fm::kFrameHeaderBytes] == static_cast<uint8_t>(fm::MaintenanceCommand::kReset) &&
         frame[fm::kFrameHeaderBytes + 1] == static_cast<uint8_t>(fm::ResultCode::kAck);
}

// Offset of a frame's sequence byte (docs/unit-protocol.md §2).
constexpr size_t kSequenceOffset = 4;

}  // namespace

UnitDevice::UnitDevice(std::string role, const fm::UnitIdentity& identity, int baud)
    : role_(std::move(role)), handler_(identity, &flash_), line_(baud, kUnitTxBufferBytes) {}

void UnitDevice::Receive(std::span<const uint8_t> bytes, double now_s) {
  if (unplugged_ || !powered_) return;
  // The handler takes at most 65,535 bytes per call; feed in chunks and re-offer the rest of a
  // chunk after each response.
  constexpr size_t kChunk = 4096;
  for (size_t start = 0; start < bytes.size(); start += kChunk) {
    const auto count = static_cast<uint16_t>(std::min(kChunk, bytes.size() - start));
    const uint8_t* chunk = bytes.data() + start;
    uint16_t consumed = 0;
    while (true) {
      const fm::PortResult result = handler_.Receive(chunk + consumed,
                                                     static_cast<uint16_t>(count - consumed),
                                                     frame_.data(),
                                                     static_cast<uint16_t>(frame_.size()));
      consumed = static_cast<uint16_t>(consumed + result.consumed_bytes);
      if (result.response_bytes == 0) break;
      // RESET is a power cycle before its ACK: whatever the line still held is lost.
      if (IsResetAck(frame_.data(), result.response_bytes)) line_.Flush(now_s);
      if (line_.Queue({frame_.data(), result.response_bytes}, now_s)) ++counters_.responses_sent;
    }
  }
}

void UnitDevice::Advance(double now_s, double, RigEnvironment& env) {
  last_now_s_ = now_s;
  // Samples fall on whole multiples of the period, however the caller slices time.
  const auto due = static_cast<uint64_t>(std::floor(now_s / kUnitSamplePeriod_s + 1e-6));
  while (samples_done_ < due) {
    ++samples_done_;
    const double sample_s = static_cast<double>(samples_done_) * kUnitSamplePeriod_s;
    const uint16_t length = Acquire(
        sample_s, env, powered_, handler_, frame_.data(), static_cast<uint16_t>(frame_.size()));
    if (length == 0) continue;
    const uint8_t seq = frame_[kSequenceOffset];
    last_index_ = last_index_ ? *last_index_ + ((seq - *last_index_) & 0xFFu) : uint64_t{seq};
    if (line_.Queue({frame_.data(), length}, sample_s)) {
      ++counters_.packets_sent;
      if (!unplugged_) packet_count_ = *last_index_ + 1;
      if (packet_log_ != nullptr) LogPacket(length);
    } else {
      ++counters_.packets_dropped;
    }
  }
}

void UnitDevice::LogPacket(uint16_t length) {
  constexpr size_t kFingerprintBytes = 8;
  char line[64];
  int n = std::snprintf(line,
                        sizeof line,
                        "%llu %u ",
                        static_cast<unsigned long long>(samples_done_),
                        static_cast<unsigned>(frame_[kSequenceOffset]));
  for (size_t i = 0; i < kFingerprintBytes && fm::kFrameHeaderBytes + i < length; ++i) {
    n += std::snprintf(line + n,
                       sizeof line - static_cast<size_t>(n),
                       "%02x",
                       static_cast<unsigned>(frame_[fm::kFrameHeaderBytes + i]));
  }
  *packet_log_ << line << '\n';
}

std::string UnitDevice::LineReport() const {
  return "packets_sent=" + std::to_string(counters_.packets_sent) +
         " packets_dropped=" + std::to_string(counters_.packets_dropped) +
         " responses_sent=" + std::to_string(counters_.responses_sent);
}

void UnitDevice::TakeOutput(double now_s, std::vector<uint8_t>& out) {
  if (!unplugged_) {
    line_.Release(now_s, out);
    return;
  }
  std::vector<uint8_t> lost;  // sent into an unplugged cable
  line_.Release(now_s, lost);
}

void UnitDevice::SetPhysicalFault(const std::string& fault, bool on) {
  if (fault == kUnplugged) {
    unplugged_ = on;
  } else if (fault == kReset) {
    if (on && powered_) line_.Flush(last_now_s_);
    if (!on && !powered_) handler_.PowerCycle();
    powered_ = !on;
  } else {
    SerialDevice::SetPhysicalFault(fault, on);
  }
}

}  // namespace adahrs::rig_sim
