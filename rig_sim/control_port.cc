#include "rig_sim/control_port.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "rig_sim/fixture_orientation.h"

namespace adahrs::rig_sim {
namespace {

std::vector<std::string> Words(std::string_view line) {
  std::istringstream in{std::string(line)};
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

double ParseNumber(const std::string& text) {
  size_t used = 0;
  double rate = 0.0;
  try {
    rate = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size()) throw std::invalid_argument("'" + text + "' is not a number");
  return rate;
}

}  // namespace

RigControl::RigControl(std::vector<ControlTarget> targets, double time_scale)
    : targets_(std::move(targets)), time_scale_(time_scale) {}

const ControlTarget& RigControl::Target(const std::string& role) const {
  for (const ControlTarget& t : targets_) {
    if (t.role == role) return t;
  }
  std::string roles;
  for (const ControlTarget& t : targets_) roles += (roles.empty() ? "" : ",") + t.role;
  throw std::invalid_argument("no role '" + role + "' (roles: " + roles + ")");
}

void RigControl::SetFault(const std::string& role,
                          const std::string& fault,
                          const std::string& value) {
  ByteFaultDevice& device = *Target(role).device;
  if (ByteFaultDevice::IsRate(fault)) {
    const double rate = ParseNumber(value);
    device.SetRate(fault, rate);
    if (rate > 0.0) {
      active_faults_[role + ":" + fault] = value;
    } else {
      active_faults_.erase(role + ":" + fault);
    }
    return;
  }
  if (value != "on" && value != "off") {
    throw std::invalid_argument(role + ": " + fault + " takes on or off, not '" + value + "'");
  }
  const bool on = value == "on";
  if (ByteFaultDevice::IsSwitch(fault)) {
    device.SetSwitch(fault, on);
  } else {
    const std::vector<std::string> physical = device.PhysicalFaults();
    if (std::find(physical.begin(), physical.end(), fault) == physical.end()) {
      std::string names;
      for (const std::string& n : ByteFaultDevice::FaultNames()) names += " " + n;
      for (const std::string& n : physical) names += " " + n;
      throw std::invalid_argument(role + ": no fault '" + fault + "' (faults:" + names + ")");
    }
    device.SetPhysicalFault(fault, on);
  }
  if (on) {
    active_faults_[role + ":" + fault] = "on";
  } else {
    active_faults_.erase(role + ":" + fault);
  }
}

std::string RigControl::Status(double now_s) const {
  std::string roles, faults;
  for (const ControlTarget& t : targets_) roles += (roles.empty() ? "" : ",") + t.role;
  roles += ",control";
  for (const auto& [key, value] : active_faults_) {
    faults += (faults.empty() ? "" : ",") + key + "=" + value;
  }
  return fmt::format("OK time_s={:.2f} time_scale={:g} roles={} faults={}",
                     now_s,
                     time_scale_,
                     roles,
                     faults.empty() ? "none" : faults);
}

std::string RigControl::Execute(std::string_view line, double now_s, RigEnvironment& env) {
  const std::vector<std::string> w = Words(line);
  if (w.empty()) return "ERR empty command";
  try {
    const std::string& cmd = w[0];
    if (cmd == "help" && w.size() == 1) {
      return "OK time | status | env | faults <role> | fault <role> <fault> on|off | "
             "fault <role> drop_rate|corrupt_rate <0..1> | orientation <imu role> [code]";
    }
    if (cmd == "time" && w.size() == 1) return fmt::format("OK {:.3f}", now_s);
    if (cmd == "status" && w.size() == 1) return Status(now_s);
    if (cmd == "env" && w.size() == 1) {
      return fmt::format(
          "OK time_s={:.3f} imu_chamber_air_c={:.3f} ads_chamber_air_c={:.3f} "
          "table_angle_deg={:.3f} table_rate_dps={:.4f} ps_pa={:.2f} qc_pa={:.2f} "
          "local_gravity_mps2={:.6f} supply_v={:.3f} imu_orientation={},{},{},{}",
          now_s,
          env.imu_chamber_air_c,
          env.ads_chamber_air_c,
          env.table_angle_deg,
          env.table_rate_dps,
          env.ps_pa,
          env.qc_pa,
          env.local_gravity_mps2,
          env.supply_v,
          env.imu_orientation[0],
          env.imu_orientation[1],
          env.imu_orientation[2],
          env.imu_orientation[3]);
    }
    if (cmd == "faults" && w.size() == 2) {
      std::string names;
      for (const std::string& n : ByteFaultDevice::FaultNames()) names += " " + n;
      for (const std::string& n : Target(w[1]).device->PhysicalFaults()) names += " " + n;
      return "OK" + names;
    }
    if (cmd == "fault" && w.size() == 4) {
      SetFault(w[1], w[2], w[3]);
      return fmt::format("OK {} {} {}", w[1], w[2], w[3]);
    }
    if (cmd == "orientation" && (w.size() == 2 || w.size() == 3)) {
      const ControlTarget& target = Target(w[1]);
      if (target.imu_slot < 0) return "ERR " + w[1] + " is not an IMU unit";
      int& code = env.imu_orientation[static_cast<size_t>(target.imu_slot)];
      if (w.size() == 3) {
        const double requested = ParseNumber(w[2]);
        if (requested != static_cast<int>(requested) ||
            !IsValidOrientation(static_cast<int>(requested))) {
          return "ERR " + w[2] + " is not a fixture code (11 12 21 22 31 32)";
        }
        code = static_cast<int>(requested);
      }
      return fmt::format("OK {} {}", w[1], code);
    }
    return "ERR unknown command '" + std::string(line) + "' (try help)";
  } catch (const std::invalid_argument& e) {
    return std::string("ERR ") + e.what();
  }
}

void ControlPortDevice::Receive(std::span<const uint8_t> bytes, double) {
  for (uint8_t b : bytes) {
    if (b == '\n') {
      if (overlong_) {
        replies_ += "ERR line too long\n";
      } else {
        lines_.push_back(partial_);
      }
      partial_.clear();
      overlong_ = false;
    } else if (b != '\r') {
      if (partial_.size() < kMaxLineBytes) {
        partial_ += static_cast<char>(b);
      } else {
        overlong_ = true;
      }
    }
  }
}

void ControlPortDevice::Advance(double now_s, double, RigEnvironment& env) {
  for (const std::string& line : lines_) replies_ += control_->Execute(line, now_s, env) + "\n";
  lines_.clear();
}

void ControlPortDevice::TakeOutput(double, std::vector<uint8_t>& out) {
  out.insert(out.end(), replies_.begin(), replies_.end());
  replies_.clear();
}

}  // namespace adahrs::rig_sim
