#include "rig_sim/prologix_adts_device.h"

#include <algorithm>

#include "common/atmosphere.h"

namespace adahrs::rig_sim {

namespace {
constexpr size_t kInstrumentInputMax = 1024;  // the ADTS input buffer (INF)
constexpr size_t kMaxIgnored = 100;
}  // namespace

PrologixAdtsDevice::PrologixAdtsDevice(std::string role, const PrologixAdtsParams& params)
    : role_(std::move(role)),
      params_(params),
      controller_(params.version_text),
      adts_(params.adts) {}

void PrologixAdtsDevice::Queue(double at_s, std::string bytes) {
  const auto later = std::upper_bound(
      output_.begin(), output_.end(), at_s, [](double t, const Pending& p) { return t < p.at_s; });
  output_.insert(later, Pending{at_s, std::move(bytes)});
}

void PrologixAdtsDevice::Receive(std::span<const uint8_t> bytes, double now_s) {
  for (const uint8_t byte : bytes) {
    const auto line = splitter_.Feed(byte);
    if (!line) continue;
    if (line->is_command) {
      HandleCommand(line->text, now_s);
    } else {
      SendToInstrument(line->text, now_s);
      if (controller_.settings().auto_read) Read(now_s, -1);
    }
  }
}

void PrologixAdtsDevice::SendToInstrument(const std::string& data, double now_s) {
  const hil::PrologixSettings& s = controller_.settings();
  if (s.mode != 1 || s.address != params_.gpib_address) return;  // nobody listening
  instrument_input_ += data;
  instrument_input_ += hil::PrologixEosTerminator(s.eos);
  if (instrument_input_.size() > kInstrumentInputMax) {
    instrument_input_.clear();
    adts_.PushError(hil::kScpiCommandError);
    return;
  }
  // Messages end at LF, or at the byte sent with EOI (the last one of this write).
  std::vector<std::string> messages;
  size_t lf;
  while ((lf = instrument_input_.find('\n')) != std::string::npos) {
    messages.push_back(instrument_input_.substr(0, lf));
    instrument_input_.erase(0, lf + 1);
  }
  if (s.eoi && !instrument_input_.empty()) messages.push_back(std::exchange(instrument_input_, {}));
  adts_.AdvanceTo(now_s);
  for (const std::string& message : messages) {
    const std::optional<std::string> reply = adts_.Execute(message);
    if (!reply) continue;
    if (response_) adts_.PushError(hil::kScpiQueryInterrupted);
    response_ = Response{now_s + params_.response_delay_s, *reply + "\n"};
  }
}

void PrologixAdtsDevice::Read(double now_s, int until_char) {
  const hil::PrologixSettings& s = controller_.settings();
  if (s.mode != 1 || s.address != params_.gpib_address || !response_) return;
  if (response_->ready_s > now_s + s.read_tmo_ms / 1000.0) return;  // timed out; reply stays queued
  std::string bytes;
  size_t end = response_->bytes.size();
  if (until_char >= 0) {
    const size_t at = response_->bytes.find(static_cast<char>(until_char));
    if (at != std::string::npos) end = at + 1;
  }
  bytes = response_->bytes.substr(0, end);
  const double at_s = std::max(now_s, response_->ready_s);
  if (end == response_->bytes.size()) {
    if (s.eot_enable) bytes.push_back(static_cast<char>(s.eot_char));  // EOI was seen
    response_.reset();
  } else {
    response_->bytes.erase(0, end);
  }
  Queue(at_s, std::move(bytes));
}

void PrologixAdtsDevice::HandleCommand(const std::string& text, double now_s) {
  const hil::PrologixAction action = controller_.Apply(text);
  const bool addressed = controller_.settings().address == params_.gpib_address;
  using Kind = hil::PrologixAction::Kind;
  switch (action.kind) {
    case Kind::kReply:
      Queue(now_s + params_.adapter_reply_delay_s, action.reply);
      break;
    case Kind::kRead:
      Read(now_s, action.read_until_eoi ? -1 : action.read_until_char);
      break;
    case Kind::kDeviceClear:
      if (addressed) {
        instrument_input_.clear();
        response_.reset();
      }
      break;
    case Kind::kSerialPoll:
      if (addressed) {
        const int stb = adts_.StatusByte(response_.has_value());
        Queue(now_s + params_.adapter_reply_delay_s, std::to_string(stb) + "\r\n");
      }
      break;
    case Kind::kReset:
      controller_.Reset();
      break;
    case Kind::kIgnored:
      if (ignored_.size() == kMaxIgnored) ignored_.pop_front();
      ignored_.push_back(action.reply);
      break;
    case Kind::kTrigger:
    case Kind::kNone:
      break;
  }
}

void PrologixAdtsDevice::Advance(double now_s, double, RigEnvironment& env) {
  adts_.AdvanceTo(now_s);
  env.ps_pa = adts_.ps_pa();
  env.qc_pa = adts_.qc_pa();
}

void PrologixAdtsDevice::TakeOutput(double now_s, std::vector<uint8_t>& out) {
  while (!output_.empty() && output_.front().at_s <= now_s) {
    out.insert(out.end(), output_.front().bytes.begin(), output_.front().bytes.end());
    output_.pop_front();
  }
}

void PrologixAdtsDevice::SetPhysicalFault(const std::string& fault, bool on) {
  if (fault != "never_stable") SerialDevice::SetPhysicalFault(fault, on);
  adts_.SetNeverStable(on);
}

std::unique_ptr<SerialDevice> MakePrologixAdtsDevice(const common::ParamReader& config) {
  PrologixAdtsParams p;
  p.gpib_address = static_cast<int>(config.Integer("gpib_address", 0, 30));
  p.version_text = config.String("version_text");
  p.adapter_reply_delay_s = config.Number("adapter_reply_delay_s", 0.0, 1.0, "s");
  p.response_delay_s = config.Number("response_delay_s", 0.0, 0.4, "s");  // §4.7: within 400 ms
  const common::ParamReader a = config.Child("adts");
  Adts405Params& q = p.adts;
  // The ISA model covers −5 km … 20 km (common/atmosphere.h): Ps limits stay inside it.
  const double isa_low_pa = common::IsaStaticPressurePa(common::kIsaMaxAltitude_m);
  const double isa_high_pa = common::IsaStaticPressurePa(common::kIsaMinAltitude_m);
  q.ps_min_pa = a.Number("ps_min_pa", isa_low_pa, isa_high_pa, "Pa");
  q.ps_max_pa = a.Number("ps_max_pa", q.ps_min_pa, isa_high_pa, "Pa");
  q.qc_max_pa = a.Number("qc_max_pa", 0.0, 90000.0, "Pa");  // subsonic only
  q.max_alt_rate_ft_per_min = a.Number("max_alt_rate_ft_per_min", 1.0, 100000.0, "ft/min");
  q.max_cas_rate_kt_per_min = a.Number("max_cas_rate_kt_per_min", 1.0, 2000.0, "kt/min");
  q.max_pressure_rate_pa_per_min = a.Number("max_pressure_rate_pa_per_min", 1.0, 1.0e6, "Pa/min");
  q.initial_alt_rate_ft_per_min =
      a.Number("initial_alt_rate_ft_per_min", 1.0, q.max_alt_rate_ft_per_min, "ft/min");
  q.initial_cas_rate_kt_per_min =
      a.Number("initial_cas_rate_kt_per_min", 1.0, q.max_cas_rate_kt_per_min, "kt/min");
  q.ps_stability_pa = a.Number("ps_stability_pa", 0.0, 100.0, "Pa");
  q.qc_stability_pa = a.Number("qc_stability_pa", 0.0, 100.0, "Pa");
  q.noise_tau_s = a.Number("noise_tau_s", 0.01, 100.0, "s");
  q.ground_ps_pa = a.Number("ground_ps_pa", q.ps_min_pa, q.ps_max_pa, "Pa");
  q.ground_band_pa = a.Number("ground_band_pa", 0.1, 1000.0, "Pa");
  q.stable_delay_s = a.Number("stable_delay_s", 0.0, 600.0, "s");
  q.oper_event_latched = a.Flag("oper_event_latched");
  q.idn = a.String("idn");
  q.seed = static_cast<uint64_t>(a.Integer("seed", 0, INT64_MAX));
  a.ExpectAllKeysUsed();
  std::string role = config.String("role");
  config.ExpectAllKeysUsed();
  return std::make_unique<PrologixAdtsDevice>(std::move(role), p);
}

nlohmann::json DefaultPrologixAdtsConfig() {
  const PrologixAdtsParams p;
  const Adts405Params& q = p.adts;
  return {
      {"role", "adts"},
      {"gpib_address", p.gpib_address},
      {"version_text", p.version_text},
      {"adapter_reply_delay_s", p.adapter_reply_delay_s},
      {"response_delay_s", p.response_delay_s},
      {"adts",
       {{"ps_min_pa", q.ps_min_pa},
        {"ps_max_pa", q.ps_max_pa},
        {"qc_max_pa", q.qc_max_pa},
        {"max_alt_rate_ft_per_min", q.max_alt_rate_ft_per_min},
        {"max_cas_rate_kt_per_min", q.max_cas_rate_kt_per_min},
        {"max_pressure_rate_pa_per_min", q.max_pressure_rate_pa_per_min},
        {"initial_alt_rate_ft_per_min", q.initial_alt_rate_ft_per_min},
        {"initial_cas_rate_kt_per_min", q.initial_cas_rate_kt_per_min},
        {"ps_stability_pa", q.ps_stability_pa},
        {"qc_stability_pa", q.qc_stability_pa},
        {"noise_tau_s", q.noise_tau_s},
        {"ground_ps_pa", q.ground_ps_pa},
        {"ground_band_pa", q.ground_band_pa},
        {"stable_delay_s", q.stable_delay_s},
        {"oper_event_latched", q.oper_event_latched},
        {"idn", q.idn},
        {"seed", q.seed}}},
  };
}

}  // namespace adahrs::rig_sim
