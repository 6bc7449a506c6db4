#include "rig_sim/rate_table_device.h"

#include "adahrs_build_paths.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

namespace adahrs::rig_sim {
namespace {

using common::ParamError;
using common::ParamReader;
using hil::AtlArgument;
using hil::AtlForm;
using hil::AtlParsed;
using hil::AtlParseStatus;

// 8N1: a start bit, eight data bits and a stop bit per byte.
constexpr double kBitsPerByte = 10.0;

// The controller functions the table's `operation` fields may bind.
struct Operation {
  const char* name;
  bool takes_argument;  // the action form takes a number
  bool has_value;       // a form may reply with a value
};
constexpr Operation kOperations[] = {
    {"rate", true, true},
    {"stop", false, false},
    {"home", false, false},
    {"acceleration", true, true},
    {"servo", true, true},
    {"setting", true, true},
    {"acknowledge", false, false},
    {"position", false, true},
    {"move", true, false},
    {"sine_amplitude", true, true},
    {"sine_frequency", true, true},
    {"sine_cycles", true, true},
    {"sine_start", false, false},
    {"measured_rate", false, true},
    {"status", false, true},
};

const Operation* FindOperation(const std::string& name) {
  for (const Operation& op : kOperations) {
    if (name == op.name) return &op;
  }
  return nullptr;
}

// Status word bits (invented; see the STA entry of the command table).
constexpr int kStatusServoOn = 1 << 0;
constexpr int kStatusAtRate = 1 << 1;
constexpr int kStatusInPosition = 1 << 2;
constexpr int kStatusMoving = 1 << 3;
constexpr int kStatusInterlockOpen = 1 << 4;

void CheckBindings(const hil::AtlCommandTable& commands, const std::string& source) {
  for (size_t i = 0; i < commands.commands().size(); ++i) {
    const hil::AtlCommandSpec& spec = commands.commands()[i];
    const std::string where =
        source + ": $.commands[" + std::to_string(i) + "] (" + spec.mnemonic + "): ";
    const Operation* op = FindOperation(spec.operation);
    if (op == nullptr) {
      throw ParamError(where + "the rate table has no operation \"" + spec.operation + "\"");
    }
    if (spec.action) {
      if ((spec.action->argument != AtlArgument::kNone) != op->takes_argument) {
        throw ParamError(where + "operation \"" + spec.operation + "\" " +
                         (op->takes_argument ? "needs" : "takes no") + " argument");
      }
      if (!spec.action->reply.empty() && !op->has_value) {
        throw ParamError(where + "operation \"" + spec.operation + "\" has no value to reply");
      }
    }
    if (spec.query && !op->has_value) {
      throw ParamError(where + "operation \"" + spec.operation + "\" has no value to query");
    }
  }
}

}  // namespace

RateTableDevice::RateTableDevice(const RateTableDeviceConfig& config,
                                 hil::AtlCommandTable commands,
                                 const std::string& commands_source)
    : config_(config),
      commands_(std::move(commands)),
      framer_(commands_.framing().max_line_chars),
      table_(config.physics, config.initial_angle_deg),
      byte_time_s_(kBitsPerByte / config.baud) {
  if (!(config.baud > 0.0)) throw std::invalid_argument("RateTableDevice: baud must be positive");
  CheckBindings(commands_, commands_source);
  for (const hil::AtlCommandSpec& spec : commands_.commands()) {
    if (spec.operation == "setting" && spec.action) settings_[spec.mnemonic] = spec.action->min;
  }
}

void RateTableDevice::Receive(std::span<const uint8_t> bytes, double now_s) {
  if (commands_.framing().echo) {
    Send(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), now_s);
  }
  for (uint8_t byte : bytes) {
    if (std::optional<hil::AtlLine> line = framer_.Push(byte)) {
      pending_.push_back({std::move(*line), now_s});
    }
  }
}

void RateTableDevice::Advance(double now_s, double, RigEnvironment& env) {
  while (!pending_.empty()) {
    const PendingLine pending = std::move(pending_.front());
    pending_.pop_front();
    table_.AdvanceTo(pending.received_s);
    Execute(pending.line, std::max(pending.received_s, table_.time_s()));
  }
  table_.AdvanceTo(now_s);
  env.table_rate_dps = table_.platter_rate_dps();
  env.table_angle_deg = table_.platter_angle_deg();
}

void RateTableDevice::TakeOutput(double now_s, std::vector<uint8_t>& out) {
  // Half a bit time of slack so that a byte due exactly at `now_s` is not held back by rounding.
  const double until_s = now_s + 0.05 * byte_time_s_;
  while (!output_.empty() && output_.front().first <= until_s) {
    out.push_back(output_.front().second);
    output_.pop_front();
  }
}

std::vector<std::string> RateTableDevice::PhysicalFaults() const {
  return {"interlock_open", "stalled"};
}

void RateTableDevice::SetPhysicalFault(const std::string& fault, bool on) {
  if (fault == "interlock_open") {
    table_.SetInterlockOpen(on);
  } else if (fault == "stalled") {
    table_.SetStalled(on);
  } else {
    SerialDevice::SetPhysicalFault(fault, on);
  }
}

void RateTableDevice::Send(std::string_view bytes, double ready_s) {
  double t_s = std::max(ready_s, line_free_s_);
  for (char c : bytes) {
    t_s += byte_time_s_;
    output_.emplace_back(t_s, static_cast<uint8_t>(c));
  }
  line_free_s_ = t_s;
}

void RateTableDevice::Execute(const hil::AtlLine& line, double at_s) {
  const AtlParsed parsed = hil::ParseAtlLine(commands_, line);
  std::string data;
  if (parsed.status == AtlParseStatus::kOk) {
    data = Perform(parsed, line.text);
  } else {
    std::optional<std::pair<double, double>> limits;
    if (parsed.status == AtlParseStatus::kOutOfRange) limits = EnforcedLimits(parsed);
    data = hil::FormatAtlError(
        hil::AtlErrorTemplateFor(commands_, parsed.status), parsed, line.text, limits);
  }
  Send(hil::FrameAtlReply(commands_.framing(), data), at_s + config_.reply_latency_s);
}

std::string RateTableDevice::Perform(const AtlParsed& parsed, const std::string& line_text) {
  const hil::AtlCommandSpec& spec = *parsed.spec;
  const AtlForm& form = parsed.query ? *spec.query : *spec.action;
  const std::string& op = spec.operation;
  const double x = parsed.argument;
  RateTableRefusal refusal = RateTableRefusal::kNone;
  if (!parsed.query) {
    if (op == "rate") {
      refusal = table_.Jog(x);
    } else if (op == "stop") {
      refusal = table_.Stop();
    } else if (op == "home") {
      refusal = table_.MoveTo(0.0);
    } else if (op == "acceleration") {
      refusal = table_.SetAcceleration(x);
    } else if (op == "servo") {
      refusal = table_.SetServo(x != 0.0);
    } else if (op == "setting") {
      settings_[spec.mnemonic] = x;
    } else if (op == "move") {
      refusal = table_.MoveTo(x);
    } else if (op == "sine_amplitude") {
      sine_amplitude_deg_ = x;
    } else if (op == "sine_frequency") {
      sine_frequency_hz_ = x;
    } else if (op == "sine_cycles") {
      sine_cycles_ = x;
    } else if (op == "sine_start") {
      refusal =
          table_.StartSine(sine_amplitude_deg_, sine_frequency_hz_, static_cast<int>(sine_cycles_));
    }
  }
  switch (refusal) {
    case RateTableRefusal::kNone:
      break;
    case RateTableRefusal::kServoOff:
      return hil::FormatAtlError(commands_.errors().servo_off, parsed, line_text);
    case RateTableRefusal::kInterlockOpen:
      return hil::FormatAtlError(commands_.errors().interlock_open, parsed, line_text);
    case RateTableRefusal::kBeyondLimit:
      if (op == "sine_start") return SineRefusal(parsed, line_text);
      return hil::FormatAtlError(
          commands_.errors().out_of_range, parsed, line_text, EnforcedLimits(parsed));
  }
  if (form.reply.empty()) return std::string();
  double value = Value(op, spec.mnemonic);
  if (op == "position") {
    // [0, 360) as printed: 359.99999 would print as 360.0000.
    const double scale = std::pow(10.0, form.decimals);
    value = std::round(value * scale) / scale;
    if (value >= 360.0) value -= 360.0;
  }
  return hil::FormatAtlValue(form, value);
}

std::string RateTableDevice::SineRefusal(const AtlParsed& parsed,
                                         const std::string& line_text) const {
  const double omega_radps = 2.0 * M_PI * sine_frequency_hz_;
  const double peak_rate_dps = sine_amplitude_deg_ * omega_radps;
  const double peak_accel_dps2 = peak_rate_dps * omega_radps;
  if (!(sine_amplitude_deg_ >= 0.0 && sine_frequency_hz_ > 0.0 && sine_cycles_ >= 1.0)) {
    return hil::FormatAtlError(commands_.errors().bad_argument, parsed, line_text);
  }
  const bool rate = peak_rate_dps > config_.physics.max_rate_dps;
  AtlParsed peak = parsed;
  peak.argument_text = fmt::format("{:.4f}", rate ? peak_rate_dps : peak_accel_dps2);
  std::string error_template = commands_.errors().out_of_range;
  for (size_t at = error_template.find("{unit}"); at != std::string::npos;
       at = error_template.find("{unit}")) {
    error_template.replace(at, 6, rate ? "deg/s" : "deg/s^2");
  }
  return hil::FormatAtlError(
      error_template,
      peak,
      line_text,
      std::make_pair(0.0, rate ? config_.physics.max_rate_dps : config_.physics.max_accel_dps2));
}

std::optional<std::pair<double, double>> RateTableDevice::EnforcedLimits(
    const AtlParsed& parsed) const {
  if (parsed.spec == nullptr || parsed.query) return std::nullopt;
  const AtlForm& form = *parsed.spec->action;
  if (parsed.spec->operation == "rate") {
    return std::make_pair(std::max(form.min, -config_.physics.max_rate_dps),
                          std::min(form.max, config_.physics.max_rate_dps));
  }
  if (parsed.spec->operation == "acceleration") {
    return std::make_pair(form.min, std::min(form.max, config_.physics.max_accel_dps2));
  }
  return std::nullopt;
}

double RateTableDevice::Value(const std::string& operation, const std::string& mnemonic) const {
  if (operation == "rate") return table_.commanded_rate_dps();
  if (operation == "acceleration") return table_.acceleration_dps2();
  if (operation == "servo") return table_.status().servo_on ? 1.0 : 0.0;
  if (operation == "setting") return settings_.at(mnemonic);
  if (operation == "position") return table_.measured_angle_deg();
  if (operation == "sine_amplitude") return sine_amplitude_deg_;
  if (operation == "sine_frequency") return sine_frequency_hz_;
  if (operation == "sine_cycles") return sine_cycles_;
  if (operation == "measured_rate") return table_.measured_rate_dps();
  const RateTableStatus s = table_.status();
  return (s.servo_on ? kStatusServoOn : 0) | (s.at_rate ? kStatusAtRate : 0) |
         (s.in_position ? kStatusInPosition : 0) | (s.moving ? kStatusMoving : 0) |
         (s.interlock_open ? kStatusInterlockOpen : 0);
}

std::string DefaultAtlCommandTablePath() {
  // In the source tree (the generated header holds its absolute path, so the path does not depend
  // on how the compiler was invoked: a compiler cache rewrites source paths relative).
  return (std::filesystem::path(ADAHRS_SOURCE_DIR) / "rig_sim" / "data" / "atl_commands.json")
      .string();
}

std::unique_ptr<SerialDevice> MakeRateTableDevice(const ParamReader& config) {
  RateTableDeviceConfig c;
  c.role = config.String("role");
  if (c.role.empty()) config.Fail(config.path() + ".role", "must not be empty");
  std::filesystem::path table_path = config.String("command_table");
  c.baud = config.Number("baud", 300.0, 115200.0, "baud");
  c.reply_latency_s = config.Number("reply_latency_s", 0.0, 1.0, "s");
  c.initial_angle_deg = config.Number("initial_angle_deg", 0.0, 360.0, "deg");
  const ParamReader p = config.Child("physics");
  RateTableParams& q = c.physics;
  q.max_rate_dps = p.Number("max_rate_dps", 1.0, 10000.0, "deg/s");
  q.max_accel_dps2 = p.Number("max_accel_dps2", 1.0, 100000.0, "deg/s^2");
  q.accel_dps2 = p.Number("accel_dps2", 0.1, 100000.0, "deg/s^2");
  q.rate_loop_tau_s = p.Number("rate_loop_tau_s", 1e-4, 10.0, "s");
  q.move_rate_dps = p.Number("move_rate_dps", 0.1, 10000.0, "deg/s");
  q.rate_ripple_ratio = p.Number("rate_ripple_ratio", 0.0, 0.001, "ratio");
  q.at_rate_band_dps = p.Number("at_rate_band_dps", 1e-6, 10.0, "deg/s");
  q.in_position_band_deg = p.Number("in_position_band_deg", 1e-6, 10.0, "deg");
  q.coast_tau_s = p.Number("coast_tau_s", 0.1, 3600.0, "s");
  p.ExpectAllKeysUsed();
  config.ExpectAllKeysUsed();
  if (q.accel_dps2 > q.max_accel_dps2) {
    p.Fail(p.path() + ".accel_dps2", "above max_accel_dps2");
  }
  if (q.move_rate_dps > q.max_rate_dps) {
    p.Fail(p.path() + ".move_rate_dps", "above max_rate_dps");
  }
  if (table_path.is_relative() && std::filesystem::is_regular_file(config.source())) {
    table_path = std::filesystem::path(config.source()).parent_path() / table_path;
  }
  const std::string source = table_path.string();
  return std::make_unique<RateTableDevice>(c, hil::AtlCommandTable::Load(source), source);
}

nlohmann::json DefaultRateTableConfig() {
  const RateTableDeviceConfig c;
  const RateTableParams& q = c.physics;
  return {{"role", c.role},
          {"command_table", DefaultAtlCommandTablePath()},
          {"baud", c.baud},
          {"reply_latency_s", c.reply_latency_s},
          {"initial_angle_deg", c.initial_angle_deg},
          {"physics",
           {{"max_rate_dps", q.max_rate_dps},
            {"max_accel_dps2", q.max_accel_dps2},
            {"accel_dps2", q.accel_dps2},
            {"rate_loop_tau_s", q.rate_loop_tau_s},
            {"move_rate_dps", q.move_rate_dps},
            {"rate_ripple_ratio", q.rate_ripple_ratio},
            {"at_rate_band_dps", q.at_rate_band_dps},
            {"in_position_band_deg", q.in_position_band_deg},
            {"coast_tau_s", q.coast_tau_s}}}};
}

}  // namespace adahrs::rig_sim
