#include "rig_sim/rig_config.h"

#include <fmt/format.h>

#include <array>
#include <filesystem>
#include <set>

#include "common/gravity.h"
#include "rig_sim/prologix_adts_device.h"
#include "rig_sim/rate_table_device.h"
#include "rig_sim/watlow_942_device.h"
#include "rig_sim/watlow_f4_device.h"
#include "sensor_sim/ads_unit.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::rig_sim {

using common::ParamReader;

const std::vector<InstrumentKind>& InstrumentKinds() {
  // Keys are the station file's instrument types (docs/station.md).
  static const std::vector<InstrumentKind> kinds = {
      {"aerosmith_atl", MakeRateTableDevice, DefaultRateTableConfig, "docs/rig/rate-table.md"},
      {"watlow_f4", MakeWatlowF4Device, DefaultWatlowF4Config, "docs/rig/watlow-f4.md"},
      {"watlow_942", MakeWatlow942Device, DefaultWatlow942Config, "docs/rig/watlow-942.md"},
      {"druck_adts_prologix",
       MakePrologixAdtsDevice,
       DefaultPrologixAdtsConfig,
       "docs/rig/adts.md"},
  };
  return kinds;
}

namespace {

constexpr int kMinBaud = 1200;
constexpr int kMaxBaud = 921600;

// Size of the array under `key` of `object` (the reader's JSON), refused unless an array of
// 0…max_count elements.
size_t ArraySize(const ParamReader& reader,
                 const nlohmann::json& object,
                 const char* key,
                 size_t max_count) {
  if (!reader.Has(key)) reader.Fail(reader.path() + "." + key, "missing key");
  const nlohmann::json& array = object.at(key);
  if (!array.is_array() || array.size() > max_count) {
    reader.Fail(reader.path() + "." + key,
                "expected an array of 0…" + std::to_string(max_count) + " objects");
  }
  if (array.empty()) {
    // Reading it as an empty number array records the key as used.
    std::array<double, 0> none;
    reader.NumberArray(key, 0.0, 0.0, "", none);
  }
  return array.size();
}

std::string ImuSerialName(uint32_t n) { return fmt::format("IMU-{:04d}", n); }
std::string AdsSerialName(uint32_t n) { return fmt::format("ADS-{:04d}", n); }

// The slot's "model" file, relative to the rig config's folder: its kind must be the slot's and
// its serial the slot's; its params are read in full here so a bad file is refused before the rig
// starts.
void ReadUnitModel(const ParamReader& unit,
                   bool imu,
                   const std::filesystem::path& base_dir,
                   UnitSlotConfig* slot) {
  std::filesystem::path file = unit.String("model");
  if (file.is_relative()) file = base_dir / file;
  const nlohmann::json model = ParamReader::LoadFile(file.string());
  const ParamReader top(model, file.string());
  const std::string kind = top.String("kind");
  if (kind != (imu ? "imu" : "ads")) {
    unit.Fail(unit.path() + ".model",
              fmt::format("{}: kind '{}' in an {} slot", file.string(), kind, imu ? "imu" : "ads"));
  }
  const ParamReader params = top.Child("params");
  const std::string serial = imu ? sensor_sim::ImuUnitParams::FromJson(params).serial
                                 : sensor_sim::AdsUnitParams::FromJson(params).serial;
  const std::string expected =
      imu ? ImuSerialName(slot->serial_number) : AdsSerialName(slot->serial_number);
  if (serial != expected) {
    unit.Fail(
        unit.path() + ".model",
        fmt::format(
            "{}: $.params.serial '{}' is not this slot's {}", file.string(), serial, expected));
  }
  slot->model_params = model["params"];
  slot->model_file = file.string();
}

UnitSlotConfig ReadUnit(const ParamReader& unit, bool imu, const std::filesystem::path& base_dir) {
  UnitSlotConfig slot;
  slot.serial_number = static_cast<uint32_t>(unit.Integer("serial_number", 0, 9999));
  slot.seed = static_cast<uint64_t>(unit.Integer("seed", 0, INT64_MAX));
  slot.baud = static_cast<int>(unit.Integer("baud", kMinBaud, kMaxBaud));
  if (imu) {
    slot.orientation = static_cast<int>(unit.Integer("orientation", 11, 32));
    if (slot.orientation % 10 < 1 || slot.orientation % 10 > 2 || slot.orientation / 10 < 1 ||
        slot.orientation / 10 > 3) {
      unit.Fail(unit.path() + ".orientation",
                fmt::format("{} is not a fixture code (11 12 21 22 31 32)", slot.orientation));
    }
  }
  if (unit.Has("model")) ReadUnitModel(unit, imu, base_dir, &slot);
  unit.ExpectAllKeysUsed();
  return slot;
}

}  // namespace

std::string ImuSerial(uint32_t serial_number) { return ImuSerialName(serial_number); }
std::string AdsSerial(uint32_t serial_number) { return AdsSerialName(serial_number); }

double RigConfig::LocalGravityMps2() const {
  return common::NormalGravityMps2(station.latitude_deg, station.height_m);
}

RigConfig RigConfig::FromJson(const nlohmann::json& json, const std::string& source) {
  const ParamReader root(json, source);
  RigConfig config;
  config.source = source;

  const ParamReader station = root.Child("station");
  config.station.name = station.String("name");
  config.station.latitude_deg = station.Number("latitude_deg", -90.0, 90.0, "deg");
  config.station.height_m = station.Number("height_m", -1000.0, 20000.0, "m");
  config.station.supply_v = station.Number("supply_v", 4.75, 5.25, "V");
  station.ExpectAllKeysUsed();

  config.time_scale = root.Number("time_scale", 0.01, 100000.0, "simulated s per wall s");
  config.initial_air_c = root.Number("initial_air_c", -60.0, 100.0, "degC");
  if (root.Has("lockstep")) config.lockstep = root.Flag("lockstep");
  if (root.Has("packet_log")) config.packet_log = root.Flag("packet_log");

  // A unit's "model" file is named relative to the config file's folder.
  const std::filesystem::path base_dir = std::filesystem::path(source).parent_path();
  const ParamReader units = root.Child("units");
  const std::string profile = units.String("model_profile");
  try {
    config.model_profile = sensor_sim::ModelProfileFromString(profile);
  } catch (const std::invalid_argument& e) {
    units.Fail(units.path() + ".model_profile", e.what());
  }
  if (units.Has("truth_variant")) {
    try {
      config.truth_variant = sensor_sim::TruthVariantFromString(units.String("truth_variant"));
    } catch (const std::invalid_argument& e) {
      units.Fail(units.path() + ".truth_variant", e.what());
    }
  }
  const nlohmann::json& units_json = json.at("units");
  const size_t imu_count = ArraySize(units, units_json, "imu", kMaxImuUnits);
  const size_t ads_count = ArraySize(units, units_json, "ads", kMaxAdsUnits);
  std::set<std::string> serials;
  for (size_t i = 0; i < imu_count; ++i) {
    const ParamReader unit = units.Element("imu", i, imu_count);
    config.imus.push_back(ReadUnit(unit, true, base_dir));
    if (!serials.insert(ImuSerial(config.imus.back().serial_number)).second) {
      unit.Fail(unit.path() + ".serial_number", "serial used twice");
    }
  }
  for (size_t i = 0; i < ads_count; ++i) {
    const ParamReader unit = units.Element("ads", i, ads_count);
    config.ads.push_back(ReadUnit(unit, false, base_dir));
    if (!serials.insert(AdsSerial(config.ads.back().serial_number)).second) {
      unit.Fail(unit.path() + ".serial_number", "serial used twice");
    }
  }
  units.ExpectAllKeysUsed();

  const ParamReader instruments = root.Child("instruments");
  for (const InstrumentKind& kind : InstrumentKinds()) {
    if (!instruments.Has(kind.name)) continue;
    // The factory reads (and so validates) its own section; the device itself is built again
    // when the rig starts.
    kind.make(instruments.Child(kind.name));
    config.instruments[kind.name] = json.at("instruments").at(kind.name);
  }
  std::string known;
  for (const InstrumentKind& kind : InstrumentKinds()) known += " " + kind.name;
  if (known.empty()) known = " (none in this build)";
  for (const auto& [key, value] : json.at("instruments").items()) {
    if (!config.instruments.contains(key)) {
      instruments.Fail(instruments.path() + "." + key, "unknown instrument kind; known:" + known);
    }
  }

  const size_t fault_count = ArraySize(root, json, "faults", 64);
  for (size_t i = 0; i < fault_count; ++i) {
    const ParamReader entry = root.Element("faults", i, fault_count);
    FaultSetting fault;
    fault.where = entry.path();
    fault.role = entry.String("role");
    fault.fault = entry.String("fault");
    fault.is_rate = entry.Has("rate");
    if (fault.is_rate) {
      fault.rate = entry.Number("rate", 0.0, 1.0, "probability per byte");
    } else {
      fault.on = entry.Flag("on");
    }
    entry.ExpectAllKeysUsed();
    config.faults.push_back(fault);
  }
  root.ExpectAllKeysUsed();
  return config;
}

RigConfig RigConfig::Load(const std::string& path) {
  return FromJson(ParamReader::LoadFile(path), path);
}

nlohmann::json DefaultRigConfig() {
  nlohmann::json imus = nlohmann::json::array();
  for (int i = 1; i <= kMaxImuUnits; ++i) {
    imus.push_back(
        {{"serial_number", i}, {"seed", 1000 + i}, {"orientation", 31}, {"baud", 115200}});
  }
  nlohmann::json instruments = nlohmann::json::object();
  for (const InstrumentKind& kind : InstrumentKinds())
    instruments[kind.name] = kind.default_config();
  return {
      {"station",
       {{"name", "virtual lab"}, {"latitude_deg", 45.0}, {"height_m", 0.0}, {"supply_v", 5.0}}},
      {"time_scale", 1.0},
      {"initial_air_c", 25.0},
      {"units",
       {{"model_profile", "truth"},
        {"truth_variant", "standard"},
        {"imu", imus},
        {"ads",
         nlohmann::json::array({{{"serial_number", 1}, {"seed", 2001}, {"baud", 115200}}})}}},
      {"instruments", instruments},
      {"faults", nlohmann::json::array()},
  };
}

}  // namespace adahrs::rig_sim
