#include "rig_sim/watlow_f4_device.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace adahrs::rig_sim {
namespace {

using hil::modbus::DecodeStatus;

constexpr double kBitsPerCharacter = 10.0;  // 8N1: start, 8 data, stop
// Tolerance for comparing simulated instants built from sums of frame periods.
constexpr double kTimeEpsilon_s = 1e-9;

// Serial Line §2.5.1.1: t3.5 = 3.5 characters, fixed at 1.75 ms above 19200 baud.
double InterFrameGapS(int baud) { return baud > 19200 ? 1.75e-3 : 3.5 * kBitsPerCharacter / baud; }

}  // namespace

WatlowF4Device::WatlowF4Device(const WatlowF4DeviceConfig& config)
    : config_(config),
      controller_(config.controller),
      chamber_(config.chamber, config.initial_air_c),
      air_c_(config.initial_air_c) {}

void WatlowF4Device::SetPhysicalFault(const std::string& fault, bool on) {
  if (fault != kCannotReachSetPoint) SerialDevice::SetPhysicalFault(fault, on);
  fault_cannot_reach_ = on;
  chamber_ = ChamberAir(ActiveChamberParams(), air_c_);
}

ChamberAirParams WatlowF4Device::ActiveChamberParams() const {
  ChamberAirParams params = config_.chamber;
  if (fault_cannot_reach_) {
    params.heat_rate_c_per_min *= config_.capacity_ratio_in_fault;
    params.cool_rate_c_per_min *= config_.capacity_ratio_in_fault;
  }
  return params;
}

void WatlowF4Device::Receive(std::span<const uint8_t> bytes, double now_s) {
  if (bytes.empty()) return;
  EndFrameOnSilence(now_s);
  last_rx_s_ = now_s;
  if (discarding_) return;
  rx_.insert(rx_.end(), bytes.begin(), bytes.end());
  if (rx_.size() > hil::modbus::kMaxFrameBytes) {
    discarding_ = true;  // longer than any RTU frame: garbage until the line is silent
    rx_.clear();
    return;
  }
  ParseBuffer(now_s);
}

void WatlowF4Device::EndFrameOnSilence(double now_s) {
  if ((rx_.empty() && !discarding_) ||
      now_s - last_rx_s_ < config_.partial_frame_timeout_s - kTimeEpsilon_s)
    return;
  // The line fell silent: what is left is one frame. Only an unknown function code with a good
  // CRC deserves a reply (exception 01); a partial known frame or garbage is dropped.
  if (!discarding_ && hil::modbus::RequestFrameLength(rx_) < 0) {
    const hil::modbus::DecodedRequest decoded = hil::modbus::DecodeRequest(rx_);
    if (decoded.status == DecodeStatus::kIllegalFunction &&
        decoded.request.address == config_.modbus_address) {
      Reply(hil::modbus::ExceptionResponse(decoded.request.address,
                                           decoded.request.function,
                                           hil::modbus::ExceptionCode::kIllegalFunction),
            now_s);
    }
  }
  rx_.clear();
  discarding_ = false;
}

void WatlowF4Device::ParseBuffer(double now_s) {
  while (!rx_.empty() && !discarding_) {
    const int length = hil::modbus::RequestFrameLength(rx_);
    if (length <= 0) return;  // more bytes needed, or delimited by silence only
    if (static_cast<size_t>(length) > hil::modbus::kMaxFrameBytes) {
      discarding_ = true;  // longer than any RTU frame: garbage
      return;
    }
    if (rx_.size() < static_cast<size_t>(length)) return;
    const std::span<const uint8_t> frame(rx_.data(), static_cast<size_t>(length));
    const hil::modbus::DecodedRequest decoded = hil::modbus::DecodeRequest(frame);
    if (decoded.status == DecodeStatus::kBadCrc) {
      discarding_ = true;
      return;
    }
    rx_.erase(rx_.begin(), rx_.begin() + length);
    const uint8_t address = decoded.request.address;
    if (address != config_.modbus_address && address != 0) continue;
    if (decoded.status == DecodeStatus::kOk) {
      Serve(decoded.request, now_s);
    } else if (decoded.status == DecodeStatus::kIllegalDataValue && address != 0) {
      Reply(hil::modbus::ExceptionResponse(
                address, decoded.request.function, hil::modbus::ExceptionCode::kIllegalDataValue),
            now_s);
    }
  }
}

void WatlowF4Device::Serve(const hil::modbus::Request& request, double now_s) {
  const hil::modbus::Response response = controller_.Handle(request);
  if (request.address != 0) Reply(response, now_s);
}

void WatlowF4Device::Reply(const hil::modbus::Response& response, double now_s) {
  const std::vector<uint8_t> frame = hil::modbus::EncodeResponse(response);
  const double character_s = kBitsPerCharacter / config_.baud;
  double end_s =
      std::max(now_s + InterFrameGapS(config_.baud) + config_.reply_latency_s, tx_free_s_);
  for (uint8_t byte : frame) {
    end_s += character_s;
    tx_.emplace_back(end_s, byte);
  }
  tx_free_s_ = end_s;
}

void WatlowF4Device::Advance(double now_s, double, RigEnvironment& env) {
  EndFrameOnSilence(now_s);
  const int64_t ticks_due =
      static_cast<int64_t>(std::floor(now_s / config_.control_tick_s + kTimeEpsilon_s));
  for (; ticks_done_ < ticks_due; ++ticks_done_) {
    const double tick_s = config_.control_tick_s;
    controller_.Tick(tick_s, air_c_);
    if (controller_.control_on()) {
      if (!chamber_driven_) chamber_ = ChamberAir(ActiveChamberParams(), air_c_);
      chamber_driven_ = true;
      air_c_ = chamber_.Step(controller_.WorkingSetPointC(), tick_s);
      controller_.SetOutputPower(chamber_.heat_fraction(), chamber_.cool_fraction());
    } else {
      controller_.SetOutputPower(0.0, 0.0);
      chamber_driven_ = false;
      air_c_ = config_.ambient_c +
               (air_c_ - config_.ambient_c) * std::exp(-tick_s / config_.control_off_tau_s);
    }
  }
  env.imu_chamber_air_c = air_c_;
}

void WatlowF4Device::TakeOutput(double now_s, std::vector<uint8_t>& out) {
  while (!tx_.empty() && tx_.front().first <= now_s + kTimeEpsilon_s) {
    out.push_back(tx_.front().second);
    tx_.pop_front();
  }
}

WatlowF4DeviceConfig ReadWatlowF4DeviceConfig(const common::ParamReader& config) {
  WatlowF4DeviceConfig c;
  c.role = config.String("role");
  c.modbus_address = static_cast<uint8_t>(config.Integer("modbus_address", 1, 247));
  c.baud = static_cast<int>(config.Integer("baud", 1200, 115200));
  c.reply_latency_s = config.Number("reply_latency_s", 0.0, 1.0, "s");
  c.partial_frame_timeout_s = config.Number("partial_frame_timeout_s", 0.001, 1.0, "s");
  c.control_tick_s = config.Number("control_tick_s", 0.01, 1.0, "s");

  const common::ParamReader controller = config.Child("controller");
  c.controller.decimals = static_cast<int>(controller.Integer("decimals", 0, 1));
  c.controller.set_point_low_limit_c =
      controller.Number("set_point_low_limit_c", -200.0, 800.0, "°C");
  c.controller.set_point_high_limit_c =
      controller.Number("set_point_high_limit_c", -200.0, 800.0, "°C");
  c.controller.static_set_point_c = controller.Number("static_set_point_c", -200.0, 800.0, "°C");
  c.controller.guaranteed_soak_band_c =
      controller.Number("guaranteed_soak_band_c", 0.0, 100.0, "°C");
  controller.ExpectAllKeysUsed();
  if (c.controller.set_point_low_limit_c >= c.controller.set_point_high_limit_c) {
    controller.Fail(controller.path(),
                    "set_point_low_limit_c must be below set_point_high_limit_c");
  }
  if (c.controller.static_set_point_c < c.controller.set_point_low_limit_c ||
      c.controller.static_set_point_c > c.controller.set_point_high_limit_c) {
    controller.Fail(controller.path() + ".static_set_point_c",
                    "must lie within the set-point limits");
  }

  const common::ParamReader chamber = config.Child("chamber");
  c.chamber.tau_s = chamber.Number("tau_s", 1.0, 36000.0, "s");
  c.chamber.heat_rate_c_per_min = chamber.Number("heat_rate_c_per_min", 0.01, 100.0, "°C/min");
  c.chamber.cool_rate_c_per_min = chamber.Number("cool_rate_c_per_min", 0.01, 100.0, "°C/min");
  c.chamber.control_band_c = chamber.Number("control_band_c", 0.0, 10.0, "°C");
  c.chamber.control_period_s = chamber.Number("control_period_s", 1.0, 3600.0, "s");
  c.chamber.min_c = chamber.Number("min_c", -200.0, 800.0, "°C");
  c.chamber.max_c = chamber.Number("max_c", -200.0, 800.0, "°C");
  c.initial_air_c = chamber.Number("initial_air_c", -200.0, 800.0, "°C");
  c.ambient_c = chamber.Number("ambient_c", -50.0, 60.0, "°C");
  c.control_off_tau_s = chamber.Number("control_off_tau_s", 1.0, 360000.0, "s");
  c.capacity_ratio_in_fault = chamber.Number("capacity_ratio_in_fault", 0.0, 1.0, "ratio");
  chamber.ExpectAllKeysUsed();
  if (c.chamber.min_c >= c.chamber.max_c) {
    chamber.Fail(chamber.path(), "min_c must be below max_c");
  }
  config.ExpectAllKeysUsed();
  return c;
}

std::unique_ptr<SerialDevice> MakeWatlowF4Device(const common::ParamReader& config) {
  return std::make_unique<WatlowF4Device>(ReadWatlowF4DeviceConfig(config));
}

nlohmann::json DefaultWatlowF4Config() {
  const WatlowF4DeviceConfig c;
  return {
      {"role", c.role},
      {"modbus_address", c.modbus_address},
      {"baud", c.baud},
      {"reply_latency_s", c.reply_latency_s},
      {"partial_frame_timeout_s", c.partial_frame_timeout_s},
      {"control_tick_s", c.control_tick_s},
      {"controller",
       {{"decimals", c.controller.decimals},
        {"set_point_low_limit_c", c.controller.set_point_low_limit_c},
        {"set_point_high_limit_c", c.controller.set_point_high_limit_c},
        {"static_set_point_c", c.controller.static_set_point_c},
        {"guaranteed_soak_band_c", c.controller.guaranteed_soak_band_c}}},
      {"chamber",
       {{"tau_s", c.chamber.tau_s},
        {"heat_rate_c_per_min", c.chamber.heat_rate_c_per_min},
        {"cool_rate_c_per_min", c.chamber.cool_rate_c_per_min},
        {"control_band_c", c.chamber.control_band_c},
        {"control_period_s", c.chamber.control_period_s},
        {"min_c", c.chamber.min_c},
        {"max_c", c.chamber.max_c},
        {"initial_air_c", c.initial_air_c},
        {"ambient_c", c.ambient_c},
        {"control_off_tau_s", c.control_off_tau_s},
        {"capacity_ratio_in_fault", c.capacity_ratio_in_fault}}},
  };
}

}  // namespace adahrs::rig_sim
