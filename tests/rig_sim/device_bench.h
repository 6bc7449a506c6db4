// Test fixture: drives one simulated serial device the way the rig does — bytes received at the
// current time, then world frames of `frame_s` (Advance) and whatever the device queued in reply
// (TakeOutput). Device tests derive their protocol helpers from it.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/param_reader.h"
#include "rig_sim/serial_device.h"

namespace adahrs::rig_sim::device_test {

class DeviceBench {
 public:
  using Factory = std::unique_ptr<SerialDevice> (*)(const common::ParamReader&);

  DeviceBench(nlohmann::json config, Factory make, double frame_s)
      : config_(std::move(config)),
        device_(make(common::ParamReader(config_, "test"))),
        frame_s_(frame_s) {}

  void Send(const std::string& text) {
    device_->Receive(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()), now_s_);
  }
  void RunFor(double duration_s) { RunUntil(now_s_ + duration_s); }
  // Whole frames up to `end_s`, then a zero-length advance to `end_s` itself.
  void RunUntil(double end_s) {
    const auto frames = static_cast<long>(std::floor(end_s / frame_s_ + 1e-9));
    for (long k = frames_done_ + 1; k <= frames; ++k) {
      device_->Advance(k * frame_s_, frame_s_, env_);
      frames_done_ = k;
    }
    if (end_s > frames_done_ * frame_s_ + 1e-9) device_->Advance(end_s, 0.0, env_);
    now_s_ = end_s;
  }
  std::string TakeAll() {
    std::vector<uint8_t> out;
    device_->TakeOutput(now_s_, out);
    return {out.begin(), out.end()};
  }
  SerialDevice& device() { return *device_; }
  double now_s() const { return now_s_; }
  RigEnvironment env_;

 private:
  nlohmann::json config_;
  std::unique_ptr<SerialDevice> device_;
  double frame_s_;
  double now_s_ = 0.0;
  long frames_done_ = 0;
};

}  // namespace adahrs::rig_sim::device_test
