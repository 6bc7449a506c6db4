#include "rig_sim/byte_faults.h"

#include <stdexcept>
#include <utility>

namespace adahrs::rig_sim {

ByteFaultDevice::ByteFaultDevice(std::unique_ptr<SerialDevice> inner, uint64_t seed)
    : inner_(std::move(inner)),
      to_device_rng_(common::Rng::Derive(seed, 1)),
      to_client_rng_(common::Rng::Derive(seed, 2)) {
  if (!inner_) throw std::invalid_argument("ByteFaultDevice around no device");
  packet_count_ = inner_->DataPacketCount();
}

std::vector<std::string> ByteFaultDevice::FaultNames() {
  return {kSilent, kGarbage, kDropRate, kCorruptRate};
}

bool ByteFaultDevice::IsSwitch(const std::string& fault) {
  return fault == kSilent || fault == kGarbage;
}

bool ByteFaultDevice::IsRate(const std::string& fault) {
  return fault == kDropRate || fault == kCorruptRate;
}

void ByteFaultDevice::SetSwitch(const std::string& fault, bool on) {
  if (fault == kSilent) {
    state_.silent = on;
  } else if (fault == kGarbage) {
    state_.garbage = on;
  } else {
    throw std::invalid_argument(role() + ": '" + fault + "' is not an on/off byte fault");
  }
}

void ByteFaultDevice::SetRate(const std::string& fault, double rate) {
  if (!IsRate(fault)) {
    throw std::invalid_argument(role() + ": '" + fault + "' is not a byte fault rate");
  }
  if (!(rate >= 0.0 && rate <= 1.0)) {
    throw std::invalid_argument(role() + ": " + fault + " " + std::to_string(rate) + " not in 0…1");
  }
  (fault == kDropRate ? state_.drop_rate : state_.corrupt_rate) = rate;
}

void ByteFaultDevice::ApplyLineNoise(std::vector<uint8_t>& bytes, size_t from, common::Rng& rng) {
  if (state_.drop_rate == 0.0 && state_.corrupt_rate == 0.0) return;
  size_t kept = from;
  for (size_t i = from; i < bytes.size(); ++i) {
    if (state_.drop_rate > 0.0 && rng.Uniform() < state_.drop_rate) {
      ++counters_.bytes_dropped;
      continue;
    }
    uint8_t b = bytes[i];
    if (state_.corrupt_rate > 0.0 && rng.Uniform() < state_.corrupt_rate) {
      b = static_cast<uint8_t>(b ^ (1u << (rng.NextU64() % 8)));
      ++counters_.bytes_corrupted;
    }
    bytes[kept++] = b;
  }
  bytes.resize(kept);
}

void ByteFaultDevice::Receive(std::span<const uint8_t> bytes, double now_s) {
  if (state_.silent) {
    counters_.bytes_silenced += bytes.size();
    return;
  }
  in_.assign(bytes.begin(), bytes.end());
  ApplyLineNoise(in_, 0, to_device_rng_);
  if (!in_.empty()) inner_->Receive(in_, now_s);
}

void ByteFaultDevice::Advance(double now_s, double dt_s, RigEnvironment& env) {
  inner_->Advance(now_s, dt_s, env);
}

void ByteFaultDevice::TakeOutput(double now_s, std::vector<uint8_t>& out) {
  const size_t from = out.size();
  inner_->TakeOutput(now_s, out);
  if (!state_.silent && !state_.garbage) packet_count_ = inner_->DataPacketCount();
  if (state_.silent) {
    counters_.bytes_silenced += out.size() - from;
    out.resize(from);
    return;
  }
  if (state_.garbage) {
    for (size_t i = from; i < out.size(); ++i)
      out[i] = static_cast<uint8_t>(to_client_rng_.NextU64());
  }
  ApplyLineNoise(out, from, to_client_rng_);
}

}  // namespace adahrs::rig_sim
