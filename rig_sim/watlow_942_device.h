// The ADS bench chamber's Watlow 942 as a serial device: the XON/XOFF ASCII link
// (hil/codecs/watlow942_codec.h, shared/protocols.md §3.3) in front of the controller model
// (rig_sim/watlow_942.h). Writes the chamber air to RigEnvironment::ads_chamber_air_c.
//
// Timing on the simulated clock: a line is acted on at the time its CR arrives (the controller is
// first brought up to that time); XOFF is released at once, then XON (and a `?` reply) after
// `reply_delay_s` (the 942's processing time, UNKNOWN, configurable). XON/XOFF from the host pause
// and resume the 942's output, as in XON/XOFF flow control. Errors are only latched in ER2
// (p. 25): a refused line is answered with XOFF XON and no data (INF).
// Physical fault: "cannot_reach_set_point" (heating/cooling failed; the air drifts to ambient).
// Left out: ANSI X3.28 multidrop framing, baud-rate pacing (the rig moves bytes at pty speed).
#pragma once

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/param_reader.h"
#include "hil/codecs/watlow942_codec.h"
#include "rig_sim/serial_device.h"
#include "rig_sim/watlow_942.h"

namespace adahrs::rig_sim {

class Watlow942Device : public SerialDevice {
 public:
  Watlow942Device(std::string role, const Watlow942Params& params, double reply_delay_s);

  const std::string& role() const override { return role_; }
  void Receive(std::span<const uint8_t> bytes, double now_s) override;
  void Advance(double now_s, double dt_s, RigEnvironment& env) override;
  void TakeOutput(double now_s, std::vector<uint8_t>& out) override;
  std::vector<std::string> PhysicalFaults() const override { return {"cannot_reach_set_point"}; }
  void SetPhysicalFault(const std::string& fault, bool on) override;

  const Watlow942& controller() const { return controller_; }

 private:
  void Queue(double at_s, std::string bytes);

  std::string role_;
  Watlow942 controller_;
  double reply_delay_s_;
  hil::Watlow942LineSplitter splitter_;
  struct Pending {
    double at_s;
    std::string bytes;
  };
  std::deque<Pending> output_;
};

/// Builds the device from its rig-config section (keys as in DefaultWatlow942Config, all
/// required and range-checked; ParamError names the JSON path).
std::unique_ptr<SerialDevice> MakeWatlow942Device(const common::ParamReader& config);

/// A complete default section for the rig config (documented in docs/rig/watlow-942.md).
nlohmann::json DefaultWatlow942Config();

}  // namespace adahrs::rig_sim
