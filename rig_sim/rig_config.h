// The rig's configuration file (JSON, docs/rig.md "Configuration"): the station (name,
// latitude_deg, height_m → local gravity by WGS-84 normal gravity, common/gravity.h; supply_v), the
// time scale, lockstep and packet_log (every unit packet's sample index logged in the run
// directory's packets/<role>.txt, UnitDevice::SetPacketLog), initial_air_c, the units on their
// ports (model_profile, truth_variant, imu and ads entries of 0…4 each: serial_number, seed, baud,
// an IMU's fixture orientation code), one section per instrument kind present (InstrumentKinds(),
// read by that instrument's factory; a kind left out is not on this rig), and the faults switched
// on at start. Every value is read through common::ParamReader: unknown keys, wrong types and
// values out of range are refused with the file and JSON path. Roles and fault names are checked
// when the rig is built (rig.h), against the devices themselves. Units in the key names (deg, m, V,
// degC); time_scale in simulated seconds per wall second. Every key with its range: docs/rig.md
// ("Configuration").
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/param_reader.h"
#include "rig_sim/serial_device.h"
#include "sensor_sim/model_profile.h"

namespace adahrs::rig_sim {

/// One kind of virtual instrument the rig can serve: its config key, factory and defaults.
struct InstrumentKind {
  std::string name;  ///< key under "instruments", the station file's `type` (docs/station.md)
  std::function<std::unique_ptr<SerialDevice>(const common::ParamReader&)> make;
  std::function<nlohmann::json()> default_config;
  std::string doc_page;  ///< docs/rig/<instrument>.md
};

/// Every instrument kind this build of the rig can serve.
const std::vector<InstrumentKind>& InstrumentKinds();

struct StationConfig {
  std::string name;
  double latitude_deg = 45.0;
  double height_m = 0.0;
  double supply_v = 5.0;
};

struct UnitSlotConfig {
  uint32_t serial_number = 1;
  uint64_t seed = 1;     ///< parameter draw; the noise stream is derived from it
  int orientation = 31;  ///< fixture code (IMU only)
  int baud = 115200;
  /// A unit file of the truth schema ("model": a rig's truth/<serial>.json, or the model.json of
  /// `adahrs diagnose --model`) whose params replace the draw; null when the slot names none. The
  /// profile and truth variant do not apply to it; the seed still sets the noise stream.
  nlohmann::json model_params;
  std::string model_file;  ///< its path, for messages
};

struct FaultSetting {
  std::string role;
  std::string fault;
  bool is_rate = false;
  bool on = false;    ///< for on/off faults
  double rate = 0.0;  ///< for drop_rate / corrupt_rate
  std::string where;  ///< JSON path, for messages
};

struct RigConfig {
  std::string source;  ///< file the config came from, for messages
  StationConfig station;
  double time_scale = 1.0;
  bool lockstep = false;
  bool packet_log = false;  ///< packets/<role>.txt: every unit packet's sample (unit_device.h)
  double initial_air_c = 25.0;
  sensor_sim::ModelProfile model_profile = sensor_sim::ModelProfile::kTruth;
  sensor_sim::TruthVariant truth_variant = sensor_sim::TruthVariant::kStandard;
  std::vector<UnitSlotConfig> imus;
  std::vector<UnitSlotConfig> ads;
  nlohmann::json instruments = nlohmann::json::object();  ///< validated sections by kind name
  std::vector<FaultSetting> faults;

  /// Station gravity from latitude and height.
  double LocalGravityMps2() const;

  /// Parses and validates; throws common::ParamError naming `source` and the JSON path.
  static RigConfig FromJson(const nlohmann::json& json, const std::string& source);
  /// Loads a file and parses it.
  static RigConfig Load(const std::string& path);
};

/// Serial name of an IMU / ADS unit: "IMU-0001", "ADS-0001".
std::string ImuSerial(uint32_t serial_number);
std::string AdsSerial(uint32_t serial_number);

/// A complete configuration: 4 IMUs and 1 ADS at 115,200 baud, every known instrument with its
/// defaults, no faults.
nlohmann::json DefaultRigConfig();

}  // namespace adahrs::rig_sim
