// Station files (docs/station.md) for the ports of a running virtual rig, split the way the lab is:
//   IMU bench: the rate table (aerosmith_atl) and the IMU chamber (watlow_f4), the units of kind
//              imu, the rig's control port as the "virtual_fixture" operator;
//   ADS bench: the ADS chamber (watlow_942) and the air data test set (druck_adts_prologix behind
//              its Prologix adapter), the units of kind ads, the same virtual-fixture operator
//              (an ADS sequence only prompts, which the fixture logs without touching the port).
// Both carry the rig's site (latitude_deg, height_m) and time scale, so the pipeline's clock and
// local gravity are the rig's. Ports are the rig's ports/<role> links from its manifest; baud,
// parity and flow are those each virtual instrument serves (docs/rig/), the addresses and the
// instrument limits (docs/station.md "Limits") those of the rig config. Each station goes through
// hil::Station::FromJson and back through ToJson, so it is validated exactly like a hand-written
// file. Left out: instruments the benches do not use; a rig without a bench's instruments gives a
// bench without them (the station reader and the sequence validation then say what is missing).
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "hil/station.h"
#include "rig_sim/rig_config.h"

namespace adahrs::rig_sim {

enum class RigBench { kImu, kAds };

/// The bench's station for the rig of `manifest` (manifest.json as the rig wrote it) started with
/// `config`; throws common::ParamError naming `source` and the JSON path if it is not valid.
hil::Station BenchStation(RigBench bench,
                          const nlohmann::json& manifest,
                          const RigConfig& config,
                          const std::string& source);

/// Writes `station` as JSON (Station::ToJson) to `path` and loads it back with Station::Load.
hil::Station WriteStationFile(const hil::Station& station, const std::filesystem::path& path);

}  // namespace adahrs::rig_sim
