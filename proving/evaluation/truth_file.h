// A simulated unit's truth file as the rig and `adahrs simulate` write it (truth/<serial>.json:
// {serial, kind, seed, model_profile, params}, docs/rig.md), read for evaluation against truth
// and for the campaign's diagnosis check. Only evaluation reads it: no calibration stage does.
// Refused with the file and JSON path: a file that is not an object with `kind` and `params`, a
// kind other than the one asked for, and a unit other than the one whose constants are judged.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "sensor_sim/ads_unit.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::proving {

struct TruthFile {
  std::string path;
  std::string kind;     ///< "imu" or "ads"
  nlohmann::json file;  ///< the whole file
};

/// Reads `path`. Throws common::ParamError naming the file and the JSON path.
TruthFile ReadTruthFile(const std::filesystem::path& path);

/// The IMU's parameters; `serial` non-empty: refused unless the file is that unit's.
sensor_sim::ImuUnitParams ImuTruth(const TruthFile& truth, const std::string& serial = "");
/// The ADS's parameters; `serial` non-empty: refused unless the file is that unit's.
sensor_sim::AdsUnitParams AdsTruth(const TruthFile& truth, const std::string& serial = "");

}  // namespace adahrs::proving
