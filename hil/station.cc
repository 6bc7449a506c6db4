#include "hil/station.h"

#include <sys/stat.h>

#include <filesystem>
#include <set>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "common/gravity.h"
#include "common/unit_kind.h"

namespace adahrs::hil {
namespace {

using common::ParamReader;

struct InstrumentRole {
  const char* role;
  InstrumentType type;
  unsigned default_baud;
};
// The instrument each role holds (reference-method.md: Aero 812 via ATL, Watlow F4 via Modbus on
// the IMU rig, Watlow 942 on the ADS bench, Druck ADTS via GPIB through a Prologix-style adapter).
constexpr InstrumentRole kRoles[] = {
    {"rate_table", InstrumentType::kAerosmithAtl, 9600},
    {"imu_chamber", InstrumentType::kWatlowF4, 9600},
    {"ads_chamber", InstrumentType::kWatlow942, 9600},
    {"adts", InstrumentType::kDruckAdtsPrologix, 115200},
};

const char* TypeName(InstrumentType type) {
  switch (type) {
    case InstrumentType::kAerosmithAtl:
      return "aerosmith_atl";
    case InstrumentType::kWatlowF4:
      return "watlow_f4";
    case InstrumentType::kWatlow942:
      return "watlow_942";
    case InstrumentType::kDruckAdtsPrologix:
      return "druck_adts_prologix";
  }
  return "?";
}

SerialSettings ReadPort(const ParamReader& r) {
  SerialSettings s;
  s.path = r.String("path");
  if (s.path.empty()) r.Fail(r.path() + ".path", "empty device path");
  s.baud = static_cast<unsigned>(r.Integer("baud", 300, 4000000));
  s.data_bits = static_cast<unsigned>(r.Integer("data_bits", 7, 8));
  const std::string parity = r.String("parity");
  if (parity != "N" && parity != "E" && parity != "O") {
    r.Fail(r.path() + ".parity", "expected \"N\", \"E\" or \"O\", got \"" + parity + "\"");
  }
  s.parity = parity[0];
  s.stop_bits = static_cast<unsigned>(r.Integer("stop_bits", 1, 2));
  const std::string flow = r.String("flow");
  if (flow == "none")
    s.flow = SerialSettings::Flow::kNone;
  else if (flow == "xonxoff")
    s.flow = SerialSettings::Flow::kSoftware;
  else if (flow == "rtscts")
    s.flow = SerialSettings::Flow::kHardware;
  else
    r.Fail(r.path() + ".flow",
           "expected \"none\", \"xonxoff\" or \"rtscts\", got \"" + flow + "\"");
  r.ExpectAllKeysUsed();
  return s;
}

nlohmann::json PortJson(const SerialSettings& s) {
  const char* flow = s.flow == SerialSettings::Flow::kSoftware   ? "xonxoff"
                     : s.flow == SerialSettings::Flow::kHardware ? "rtscts"
                                                                 : "none";
  return {{"path", s.path},
          {"baud", s.baud},
          {"data_bits", s.data_bits},
          {"parity", std::string(1, s.parity)},
          {"stop_bits", s.stop_bits},
          {"flow", flow}};
}

// What makes two port paths one port: the device they lead to (a symlink and its /dev/pts target,
// two spellings of one path), or the path itself, made absolute and normal, when nothing exists
// there yet (a station written before its rig runs).
struct PortIdentity {
  bool device = false;
  uint64_t dev = 0, ino = 0;
  std::string path;
  bool operator==(const PortIdentity&) const = default;
};

PortIdentity IdentityOf(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISCHR(st.st_mode)) return {true, static_cast<uint64_t>(st.st_rdev), 0, ""};
    return {true, static_cast<uint64_t>(st.st_dev), static_cast<uint64_t>(st.st_ino), ""};
  }
  return {false, 0, 0, std::filesystem::absolute(path).lexically_normal().string()};
}

// One end pair of a range: both ends or neither, the low one below the high one.
void ReadRange(const ParamReader& r,
               std::optional<double>& low,
               std::optional<double>& high,
               const char* low_key,
               const char* high_key,
               double min,
               double max,
               const char* unit) {
  if (!r.Has(low_key) && !r.Has(high_key)) return;
  if (!r.Has(low_key) || !r.Has(high_key)) {
    r.Fail(r.path() + "." + (r.Has(low_key) ? high_key : low_key),
           std::string("missing: a range states ") + low_key + " and " + high_key + " together");
  }
  low = r.Number(low_key, min, max, unit);
  high = r.Number(high_key, min, max, unit);
  if (!(*low < *high)) {
    r.Fail(r.path() + "." + high_key,
           fmt::format(
               "{} {:g} {} is not above {} {:g} {}", high_key, *high, unit, low_key, *low, unit));
  }
}

// The entry's optional "limits": the keys of its instrument type, each optional, each within
// what an instrument of the kind could have (a wider value is a typo or a wrong unit).
InstrumentLimits ReadLimits(const ParamReader& ir, InstrumentType type) {
  InstrumentLimits l;
  if (!ir.Has("limits")) return l;
  const ParamReader lr = ir.Child("limits");
  const auto number =
      [&](std::optional<double>& out, const char* key, double min, double max, const char* unit) {
        if (lr.Has(key)) out = lr.Number(key, min, max, unit);
      };
  switch (type) {
    case InstrumentType::kAerosmithAtl:
      number(l.max_rate_dps, "max_rate_dps", 1.0, 10000.0, "deg/s");
      number(l.max_accel_dps2, "max_accel_dps2", 0.1, 100000.0, "deg/s^2");
      break;
    case InstrumentType::kWatlowF4:
    case InstrumentType::kWatlow942:
      ReadRange(lr, l.min_c, l.max_c, "min_c", "max_c", -200.0, 500.0, "degC");
      number(l.max_ramp_c_per_min, "max_ramp_c_per_min", 0.01, 1000.0, "degC/min");
      number(l.heat_rate_c_per_min, "heat_rate_c_per_min", 0.01, 1000.0, "degC/min");
      number(l.cool_rate_c_per_min, "cool_rate_c_per_min", 0.01, 1000.0, "degC/min");
      break;
    case InstrumentType::kDruckAdtsPrologix:
      ReadRange(lr, l.ps_min_pa, l.ps_max_pa, "ps_min_pa", "ps_max_pa", 1.0, 1e6, "Pa");
      number(l.qc_max_pa, "qc_max_pa", 1.0, 1e6, "Pa");
      number(l.max_alt_rate_ft_per_min, "max_alt_rate_ft_per_min", 1.0, 1e6, "ft/min");
      number(l.max_cas_rate_kt_per_min, "max_cas_rate_kt_per_min", 1.0, 1e5, "kt/min");
      break;
  }
  lr.ExpectAllKeysUsed();
  return l;
}

// The optional "interlocks" object: thresholds within what still tells a right mounting from a
// wrong one (a wider value is a typo), attempts 1…10.
InterlockSettings ReadInterlocks(const ParamReader& r) {
  InterlockSettings s;
  if (!r.Has("interlocks")) return s;
  const ParamReader ir = r.Child("interlocks");
  if (ir.Has("relative_tolerance_g"))
    s.relative_tolerance_g = ir.Number("relative_tolerance_g", 0.01, 1.0, "g");
  if (ir.Has("first_check_margin_g"))
    s.first_check_margin_g = ir.Number("first_check_margin_g", 0.01, 2.0, "g");
  if (ir.Has("min_gyro_response"))
    s.min_gyro_response = ir.Number("min_gyro_response", 0.01, 1.0, "ratio");
  if (ir.Has("max_gyro_response"))
    s.max_gyro_response = ir.Number("max_gyro_response", 1.0, 10.0, "ratio");
  if (ir.Has("attempts")) s.attempts = static_cast<int>(ir.Integer("attempts", 1, 10));
  ir.ExpectAllKeysUsed();
  return s;
}

nlohmann::json InterlocksJson(const InterlockSettings& s) {
  nlohmann::json j = nlohmann::json::object();
  if (s.relative_tolerance_g) j["relative_tolerance_g"] = *s.relative_tolerance_g;
  if (s.first_check_margin_g) j["first_check_margin_g"] = *s.first_check_margin_g;
  if (s.min_gyro_response) j["min_gyro_response"] = *s.min_gyro_response;
  if (s.max_gyro_response) j["max_gyro_response"] = *s.max_gyro_response;
  if (s.attempts) j["attempts"] = *s.attempts;
  return j;
}

nlohmann::json LimitsJson(const InstrumentLimits& l) {
  nlohmann::json j = nlohmann::json::object();
  const auto put = [&](const char* key, const std::optional<double>& value) {
    if (value) j[key] = *value;
  };
  put("max_rate_dps", l.max_rate_dps);
  put("max_accel_dps2", l.max_accel_dps2);
  put("min_c", l.min_c);
  put("max_c", l.max_c);
  put("max_ramp_c_per_min", l.max_ramp_c_per_min);
  put("heat_rate_c_per_min", l.heat_rate_c_per_min);
  put("cool_rate_c_per_min", l.cool_rate_c_per_min);
  put("ps_min_pa", l.ps_min_pa);
  put("ps_max_pa", l.ps_max_pa);
  put("qc_max_pa", l.qc_max_pa);
  put("max_alt_rate_ft_per_min", l.max_alt_rate_ft_per_min);
  put("max_cas_rate_kt_per_min", l.max_cas_rate_kt_per_min);
  return j;
}

}  // namespace

std::string ToString(InstrumentType type) { return TypeName(type); }
std::string ToString(OperatorType type) {
  return type == OperatorType::kVirtualFixture ? "virtual_fixture" : "console";
}

Station Station::Load(const std::string& file_path) {
  const nlohmann::json j = ParamReader::LoadFile(file_path);
  return FromJson(ParamReader(j, file_path));
}

Station Station::FromJson(const ParamReader& r) {
  Station st;
  st.name = r.String("name");
  st.time_scale = r.Number("time_scale", 0.01, 1e6, "clock s per wall s");
  if (r.Has("clock_file")) st.clock_file = r.String("clock_file");
  const ParamReader site = r.Child("site");
  st.latitude_deg = site.Number("latitude_deg", -90.0, 90.0, "deg");
  st.height_m = site.Number("height_m", -500.0, 5000.0, "m");
  site.ExpectAllKeysUsed();
  st.local_gravity_mps2 = common::NormalGravityMps2(st.latitude_deg, st.height_m);

  std::vector<std::pair<PortIdentity, std::string>> claimed;  // identity, the path that claimed it
  const auto claim_path = [&](const ParamReader& where, const std::string& path) {
    const PortIdentity id = IdentityOf(path);
    for (const auto& [other, other_path] : claimed) {
      if (other != id) continue;
      where.Fail(where.path() + ".port.path",
                 other_path == path ? "port " + path + " is already used by another role"
                                    : "port " + path + " is the device " + other_path +
                                          " already used by another role");
    }
    claimed.emplace_back(id, path);
  };
  const ParamReader instruments = r.Child("instruments");
  for (const InstrumentRole& role : kRoles) {
    if (!instruments.Has(role.role)) continue;
    const ParamReader ir = instruments.Child(role.role);
    InstrumentEntry e;
    e.role = role.role;
    e.type = role.type;
    const std::string type = ir.String("type");
    if (type != TypeName(role.type)) {
      ir.Fail(ir.path() + ".type",
              "role " + e.role + " holds a " + TypeName(role.type) + ", not \"" + type + "\"");
    }
    e.port = ReadPort(ir.Child("port"));
    claim_path(ir, e.port.path);
    e.address = static_cast<int>(ir.Integer("address", 0, 247));
    e.timeout_ms = static_cast<int>(ir.Integer("timeout_ms", 10, 60000));
    e.retries = static_cast<int>(ir.Integer("retries", 0, 10));
    e.limits = ReadLimits(ir, e.type);
    ir.ExpectAllKeysUsed();
    st.instruments.push_back(e);
  }
  instruments.ExpectAllKeysUsed();

  const size_t n_units = r.ArrayLength("units", 0, 8);
  std::set<std::string> roles;
  int imus = 0;
  for (size_t i = 0; i < n_units; ++i) {
    const ParamReader ur = r.Element("units", i, n_units);
    UnitEntry u;
    u.role = ur.String("role");
    if (!roles.insert(u.role).second) ur.Fail(ur.path() + ".role", "duplicate role " + u.role);
    const std::string kind = ur.String("kind");
    const std::optional<UnitKind> parsed = common::ParseUnitKind(kind);
    if (!parsed) ur.Fail(ur.path() + ".kind", "expected \"imu\" or \"ads\", got \"" + kind + "\"");
    u.kind = *parsed;
    if (u.kind == UnitKind::kImu && ++imus > 4) {
      ur.Fail(ur.path(), "a batch holds at most 4 IMU units (the fixture has 4 slots)");
    }
    u.port = ReadPort(ur.Child("port"));
    claim_path(ur, u.port.path);
    u.slot = static_cast<int>(ur.Integer("slot", 1, 4));
    for (const UnitEntry& other : st.units) {
      if (other.kind == u.kind && other.slot == u.slot) {
        ur.Fail(ur.path() + ".slot",
                "slot " + std::to_string(u.slot) + " already holds " + other.role);
      }
    }
    u.timeout_ms = static_cast<int>(ur.Integer("timeout_ms", 10, 60000));
    ur.ExpectAllKeysUsed();
    st.units.push_back(u);
  }
  if (r.Has("operator")) {
    const ParamReader orr = r.Child("operator");
    const std::string type = orr.String("type");
    if (type == "virtual_fixture") {
      st.op.type = OperatorType::kVirtualFixture;
      st.op.port = ReadPort(orr.Child("port"));
      claim_path(orr, st.op.port.path);
    } else if (type != "console") {
      orr.Fail(orr.path() + ".type",
               "expected \"console\" or \"virtual_fixture\", got \"" + type + "\"");
    }
    orr.ExpectAllKeysUsed();
  }
  st.interlocks = ReadInterlocks(r);
  r.ExpectAllKeysUsed();
  return st;
}

nlohmann::json Station::ToJson() const {
  nlohmann::json instruments = nlohmann::json::object();
  for (const InstrumentEntry& e : this->instruments) {
    nlohmann::json& entry = instruments[e.role];
    entry = {{"type", TypeName(e.type)},
             {"port", PortJson(e.port)},
             {"address", e.address},
             {"timeout_ms", e.timeout_ms},
             {"retries", e.retries}};
    if (nlohmann::json limits = LimitsJson(e.limits); !limits.empty()) entry["limits"] = limits;
  }
  nlohmann::json units = nlohmann::json::array();
  for (const UnitEntry& u : this->units) {
    units.push_back({{"role", u.role},
                     {"kind", common::UnitKindName(u.kind)},
                     {"port", PortJson(u.port)},
                     {"slot", u.slot},
                     {"timeout_ms", u.timeout_ms}});
  }
  nlohmann::json op_json = {{"type", ToString(op.type)}};
  if (op.type == OperatorType::kVirtualFixture) op_json["port"] = PortJson(op.port);
  nlohmann::json j = {{"name", name},
                      {"time_scale", time_scale},
                      {"site", {{"latitude_deg", latitude_deg}, {"height_m", height_m}}},
                      {"instruments", instruments},
                      {"units", units},
                      {"operator", op_json}};
  if (!clock_file.empty()) j["clock_file"] = clock_file;
  if (nlohmann::json i = InterlocksJson(interlocks); !i.empty()) j["interlocks"] = i;
  return j;
}

const InstrumentEntry* Station::Instrument(const std::string& role) const {
  for (const InstrumentEntry& e : instruments) {
    if (e.role == role) return &e;
  }
  return nullptr;
}

}  // namespace adahrs::hil
