// Test helper: an ADS calibration or acceptance recording written in-process as the executor
// would (docs/recording-format.md): the sequence file is run against one simulated ADS unit by the
// studies' run simulator (proving/studies/ads_run_simulator.h: an exact air data test set whose
// pressures move as monotone jumps, the chamber air at its set point at once and the soak at frame
// rate, 1 s of untagged packets per WaitAdtsStable, no packet lost) and every packet written to
// ads.csv.
#pragma once

#include <filesystem>
#include <string>

#include "adahrs_build_paths.h"
#include "calib/sequence/sequence_json.h"
#include "hil/recording/recording_writer.h"
#include "proving/studies/ads_run_simulator.h"
#include "sensor_sim/ads_unit.h"

namespace adahrs::calib::testing {

inline std::string ShippedSequencePath(const std::string& name) {
  return std::string(ADAHRS_SOURCE_DIR) + "/calib/sequences/" + name + ".json";
}

/// Runs sequence file `sequence_path` on a unit with `params` and writes the run to `run_dir`.
inline void WriteAdsRecording(const std::filesystem::path& run_dir,
                              const std::string& sequence_path,
                              const sensor_sim::AdsUnitParams& params,
                              uint64_t noise_seed) {
  const ParsedSequence parsed = ParseSequenceFile(sequence_path);
  hil::RecordingWriter writer(run_dir, hil::RecordingStorage::kPlainCsv);  // tests edit it
  writer.WriteMetaJson({{"run_id", "ads-test"},
                        {"status", "complete"},
                        {"sample_rate_hz", 100},
                        {"units", {{{"kind", "ads"}, {"serial", params.serial}}}},
                        {"rejected_intervals", nlohmann::json::array()}});
  proving::AdsRunSimulator simulator(params, noise_seed);
  simulator.Run(parsed.sequence, [&](const hil::AdsRecordRow& row) { writer.Append(row); });
  writer.Flush(true);
}

}  // namespace adahrs::calib::testing
