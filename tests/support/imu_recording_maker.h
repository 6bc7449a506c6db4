// Test helper: makes IMU recordings in-process exactly as the executor writes them
// (docs/recording-format.md) without a rig: the product's in-process runner
// (proving/studies/imu_run_simulator.h) drives the simulated units through a sequence and every
// packet is written with hil::RecordingWriter. Time is compressed where the physics allows it:
// target_temperature soaks last `soak_frames`, and thermal profile ramps and soaks run
// `thermal_speedup` times faster than written. That is exact for units without die lag
// (ModelProfile::kNominal); with lag on, the ramps would bias the fit. truth/<serial>.json holds
// each unit's parameters, as the rig writes it.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <variant>
#include <vector>
#include "adahrs_build_paths.h"

#include <nlohmann/json.hpp>

#include "calib/sequence/sequence.h"
#include "calib/sequence/sequence_json.h"
#include "hil/recording/recording_writer.h"
#include "proving/studies/imu_run_simulator.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::calib::testing {

struct MakerOptions {
  int settle_frames = 50;  // > 10 filter time constants (3.2 ms accel, 4 ms gyro)
  int soak_frames = 100;
  double thermal_speedup = 30.0;
  double table_rate_error_dps = 0.004;
  double initial_air_temp_c = 25.0;
};

class ImuRecordingMaker {
 public:
  ImuRecordingMaker(std::vector<sensor_sim::ImuUnitParams> units,
                    double g_local_mps2,
                    uint64_t noise_seed,
                    MakerOptions options = {})
      : simulator_(std::move(units),
                   g_local_mps2,
                   noise_seed,
                   {options.settle_frames,
                    options.soak_frames,
                    options.thermal_speedup,
                    options.table_rate_error_dps,
                    options.initial_air_temp_c}),
        g_local_mps2_(g_local_mps2) {}

  /// Runs `sequence` and writes `run_dir` (meta.json, imu.csv, ads.csv, truth/).
  void Run(const Sequence& sequence, const std::filesystem::path& run_dir) {
    std::filesystem::remove_all(run_dir);
    hil::RecordingWriter writer(run_dir, hil::RecordingStorage::kPlainCsv);  // tests edit it
    const auto& params = simulator_.params();
    nlohmann::json units = nlohmann::json::array();
    for (size_t i = 0; i < params.size(); ++i) {
      units.push_back({{"role", "imu" + std::to_string(i + 1)},
                       {"kind", "imu"},
                       {"serial", params[i].serial},
                       {"serial_number", i + 1},
                       {"firmware", "1.0.0"},
                       {"slot", i + 1},
                       {"constants_version", 0},
                       {"mode", 0}});
    }
    nlohmann::json meta = {{"run_id", sequence.name},
                           {"started_utc", "2024-05-01T12:00:00Z"},
                           {"status", "complete"},
                           {"sequence", nlohmann::json::parse(SequenceToJson(sequence).dump())},
                           {"sequence_file", sequence.name + ".json"},
                           {"time_base", "pipeline clock seconds since the run started"},
                           {"sample_rate_hz", 100},
                           {"local_gravity_mps2", g_local_mps2_},
                           {"units", units},
                           {"instruments", nlohmann::json::array()},
                           {"rejected_intervals", nlohmann::json::array()}};
    simulator_.Run(sequence, [&writer](const hil::ImuRecordRow& row) { writer.Append(row); });
    writer.WriteMetaJson(meta);
    writer.Flush(true);
    std::filesystem::create_directories(run_dir / "truth");
    for (const auto& p : params)
      std::ofstream(run_dir / "truth" / (p.serial + ".json")) << p.ToJson().dump(2);
  }

 private:
  proving::ImuRunSimulator simulator_;
  double g_local_mps2_;
};

/// A shipped sequence (calib/sequences/<name>.json) with every acquisition's packet count set to
/// `packets` (short recordings for tests).
inline Sequence ShippedSequence(const std::string& name, int64_t packets) {
  Sequence s = SequenceFromJson(common::ParamReader::LoadFile(std::string(ADAHRS_SOURCE_DIR) +
                                                              "/calib/sequences/" + name + ".json"),
                                name);
  for (Step& step : s.steps) {
    if (auto* a = std::get_if<AccelStep>(&step.body)) a->packets = packets;
    if (auto* g = std::get_if<GyroStep>(&step.body)) g->packets = packets;
    if (auto* c = std::get_if<CrossAxisStep>(&step.body)) c->packets = packets;
  }
  return s;
}

}  // namespace adahrs::calib::testing
