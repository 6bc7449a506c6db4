// A Prologix-compatible GPIB-USB adapter (shared/protocols.md §6) with the virtual Druck ADTS 405
// (rig_sim/adts405.h) at one GPIB address behind it, as one serial device of the rig. Writes the
// delivered pressures to RigEnvironment::ps_pa and qc_pa.
//
// Host lines are split and `++` commands interpreted by hil/codecs/prologix.h. A data line goes
// to the ADTS (CONTROLLER mode, `++addr` = the ADTS address; otherwise nobody listens) with the
// `++eos` terminator appended and EOI on its last byte when `++eoi 1`; the ADTS takes a message as
// complete at LF or EOI (protocols.md §4.2, INF) and queues its response (text + LF, EOI on the LF)
// `response_delay_s` later (§4.7: "responds to commands within 400 ms"). `++read eoi` (or
// `++auto 1` after each data line) passes the response to the host once it is ready, if that is
// within `++read_tmo_ms`; otherwise nothing comes, as from the real adapter after its timeout.
// A new response replaces an unread one (IEEE 488.2 query interrupted, error −410).
// All timing is on the simulated clock. Physical fault: "never_stable" (the ADTS).
// Left out: DEVICE mode behaviour (data is dropped), serial-poll of other addresses, ++lon,
// a "raw" GPIB port without the ++ layer.
#pragma once

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/param_reader.h"
#include "hil/codecs/prologix.h"
#include "rig_sim/adts405.h"
#include "rig_sim/serial_device.h"

namespace adahrs::rig_sim {

struct PrologixAdtsParams {
  int gpib_address = 1;
  std::string version_text = "Prologix GPIB-USB Controller version 6.107";
  double adapter_reply_delay_s = 0.002;
  double response_delay_s = 0.02;
  Adts405Params adts;
};

class PrologixAdtsDevice : public SerialDevice {
 public:
  PrologixAdtsDevice(std::string role, const PrologixAdtsParams& params);

  const std::string& role() const override { return role_; }
  void Receive(std::span<const uint8_t> bytes, double now_s) override;
  void Advance(double now_s, double dt_s, RigEnvironment& env) override;
  void TakeOutput(double now_s, std::vector<uint8_t>& out) override;
  std::vector<std::string> PhysicalFaults() const override { return {"never_stable"}; }
  void SetPhysicalFault(const std::string& fault, bool on) override;
  std::optional<int> GpibAddress() const override { return params_.gpib_address; }

  const Adts405& adts() const { return adts_; }
  /// `++` commands the adapter ignored (unknown or bad argument), with the reason; the last 100.
  const std::deque<std::string>& ignored_commands() const { return ignored_; }

 private:
  void HandleCommand(const std::string& text, double now_s);
  void SendToInstrument(const std::string& data, double now_s);
  void Read(double now_s, int until_char);
  void Queue(double at_s, std::string bytes);

  std::string role_;
  PrologixAdtsParams params_;
  hil::PrologixLineSplitter splitter_;
  hil::PrologixController controller_;
  Adts405 adts_;
  std::string instrument_input_;  // bytes received by the ADTS since its last complete message
  struct Response {
    double ready_s;
    std::string bytes;  // ends with the LF sent with EOI
  };
  std::optional<Response> response_;
  struct Pending {
    double at_s;
    std::string bytes;
  };
  std::deque<Pending> output_;  // ordered by at_s
  std::deque<std::string> ignored_;
};

/// Builds the device from its rig-config section (keys as in DefaultPrologixAdtsConfig, all
/// required and range-checked; ParamError names the JSON path).
std::unique_ptr<SerialDevice> MakePrologixAdtsDevice(const common::ParamReader& config);

/// A complete default section for the rig config (documented in docs/rig/adts.md).
nlohmann::json DefaultPrologixAdtsConfig();

}  // namespace adahrs::rig_sim
