#include "rig_sim/watlow_942_device.h"

namespace adahrs::rig_sim {

Watlow942Device::Watlow942Device(std::string role,
                                 const Watlow942Params& params,
                                 double reply_delay_s)
    : role_(std::move(role)), controller_(params), reply_delay_s_(reply_delay_s) {}

void Watlow942Device::Queue(double at_s, std::string bytes) {
  output_.push_back({at_s, std::move(bytes)});
}

void Watlow942Device::Receive(std::span<const uint8_t> bytes, double now_s) {
  for (const uint8_t byte : bytes) {
    const auto line = splitter_.Feed(byte);
    if (!line) continue;
    controller_.AdvanceTo(now_s);
    Queue(now_s, std::string{static_cast<char>(hil::kWatlow942Xoff)});
    std::optional<std::vector<std::string>> fields;
    if (line->overflowed) {
      controller_.LatchError(hil::Watlow942Error::kRxOverflow);
    } else {
      const hil::Watlow942Decoded decoded = hil::DecodeWatlow942Line(line->text);
      if (decoded.message) {
        fields = controller_.Handle(*decoded.message);
      } else {
        controller_.LatchError(decoded.error);
      }
    }
    std::string reply{static_cast<char>(hil::kWatlow942Xon)};
    if (fields) reply = hil::EncodeWatlow942ReadReply(*fields).substr(1);  // XOFF already sent
    Queue(now_s + reply_delay_s_, std::move(reply));
  }
}

void Watlow942Device::Advance(double now_s, double, RigEnvironment& env) {
  controller_.AdvanceTo(now_s);
  env.ads_chamber_air_c = controller_.air_c();
}

void Watlow942Device::TakeOutput(double now_s, std::vector<uint8_t>& out) {
  if (splitter_.flow_paused()) return;
  while (!output_.empty() && output_.front().at_s <= now_s) {
    out.insert(out.end(), output_.front().bytes.begin(), output_.front().bytes.end());
    output_.pop_front();
  }
}

void Watlow942Device::SetPhysicalFault(const std::string& fault, bool on) {
  if (fault != "cannot_reach_set_point") SerialDevice::SetPhysicalFault(fault, on);
  controller_.SetCannotReachSetPoint(on);
}

std::unique_ptr<SerialDevice> MakeWatlow942Device(const common::ParamReader& config) {
  Watlow942Params p;
  const common::ParamReader air = config.Child("air");
  p.air.tau_s = air.Number("tau_s", 1.0, 1e5, "s");
  p.air.heat_rate_c_per_min = air.Number("heat_rate_c_per_min", 0.01, 100.0, "°C/min");
  p.air.cool_rate_c_per_min = air.Number("cool_rate_c_per_min", 0.01, 100.0, "°C/min");
  p.air.control_band_c = air.Number("control_band_c", 0.0, 5.0, "°C");
  p.air.control_period_s = air.Number("control_period_s", 1.0, 1e4, "s");
  p.air.min_c = air.Number("min_c", -100.0, 50.0, "°C");
  p.air.max_c = air.Number("max_c", 0.0, 300.0, "°C");
  air.ExpectAllKeysUsed();
  p.initial_air_c = config.Number("initial_air_c", p.air.min_c, p.air.max_c, "°C");
  p.ambient_c = config.Number("ambient_c", p.air.min_c, p.air.max_c, "°C");
  p.range_low_c = config.Number("range_low_c", p.air.min_c, p.air.max_c, "°C");
  p.range_high_c = config.Number("range_high_c", p.range_low_c, p.air.max_c, "°C");
  p.initial_set_point_c = config.Number("initial_set_point_c", p.range_low_c, p.range_high_c, "°C");
  p.max_ramp_rate_c_per_min = config.Number("max_ramp_rate_c_per_min", 0.1, 999.9, "°C/min");
  const std::string profile_type = config.String("profile_type");
  if (profile_type != "rate" && profile_type != "time") {
    config.Fail(config.path() + ".profile_type",
                "expected \"rate\" or \"time\", got \"" + profile_type + "\"");
  }
  p.profile_by_rate = profile_type == "rate";
  p.decimals = static_cast<int>(config.Integer("decimals", 0, 2));
  p.software_revision = static_cast<int>(config.Integer("software_revision", 0, 9));
  const double reply_delay_s = config.Number("reply_delay_s", 0.0, 1.0, "s");
  std::string role = config.String("role");
  config.ExpectAllKeysUsed();
  return std::make_unique<Watlow942Device>(std::move(role), p, reply_delay_s);
}

nlohmann::json DefaultWatlow942Config() {
  const Watlow942Params p;
  return {
      {"role", "ads_chamber"},
      {"air",
       {{"tau_s", p.air.tau_s},
        {"heat_rate_c_per_min", p.air.heat_rate_c_per_min},
        {"cool_rate_c_per_min", p.air.cool_rate_c_per_min},
        {"control_band_c", p.air.control_band_c},
        {"control_period_s", p.air.control_period_s},
        {"min_c", p.air.min_c},
        {"max_c", p.air.max_c}}},
      {"initial_air_c", p.initial_air_c},
      {"ambient_c", p.ambient_c},
      {"range_low_c", p.range_low_c},
      {"range_high_c", p.range_high_c},
      {"initial_set_point_c", p.initial_set_point_c},
      {"max_ramp_rate_c_per_min", p.max_ramp_rate_c_per_min},
      {"profile_type", "rate"},
      {"decimals", p.decimals},
      {"software_revision", p.software_revision},
      {"reply_delay_s", 0.05},
  };
}

}  // namespace adahrs::rig_sim
