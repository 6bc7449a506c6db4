// The rig's configuration file (JSON, docs/rig.md "Configuration"): the station, the time scale,
// the units on their ports, the instruments and the faults switched on at start.
//
//   station      name, latitude_deg, height_m (→ local gravity, WGS-84 normal gravity,
//                common/gravity.h), supply_v (the units' supply rail)
//   time_scale   simulated seconds per wall second (0.01…100,000; --time-scale overrides it)
//   lockstep     optional, default false: the clock waits for slow readers and time_scale is
//                its top speed (rig_sim/device_host.h; --lockstep sets it)
//   initial_air_c  air in both chambers and every die at power-on
//   units        model_profile ("nominal" or "truth"), truth_variant (optional: "standard",
//                "play_hysteresis" or "slow_bias_wander", sensor_sim/model_profile.h),
//                imu: 0…4 entries, ads: 0…4 entries, each
//                {serial_number, seed, baud} and for IMUs the fixture orientation code
//   instruments  one section per instrument kind present (InstrumentKinds()), read by that
//                instrument's own factory; a kind left out is not on this rig
//   faults       [{role, fault, on} | {role, fault, rate}] applied before the clock starts
// Every value is read through common::ParamReader: unknown keys, wrong types and values out
// of range are refused with the file and JSON path. Roles and fault names are checked when the
// rig is built (rig.h), against the devices themselves.
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
