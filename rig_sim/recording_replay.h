// Re-simulation of a recording's stimulus (`adahrs simulate replay`): each unit of a run directory
// is driven by a unit model file (the truth schema {kind, params}: a rig's truth/<serial>.json, or
// the augmented model.json `adahrs diagnose --model` writes) with the recording's own reference
// columns, and a run of the same rows is written with the model's raw outputs in place of the
// recorded ones. Comparing the two says how well the model explains the recording. A row takes the
// frames since the unit's previous row from the recording's frame column (version 3), else those
// its packet counter (seq) moved plus the 256-frame turns the arrival times say passed; rows
// before an instrument's first report take that report's values.
// Frames and units: IMU stimulus 1 local g (meta.json local_gravity_mps2) and the table rate along
// the up axis of the row's fixture code, body frame; ADS the reference ps and qc in Pa; chamber
// column in degC as the air around the unit.
// Stimulus, power-on time, frame counting and the zero-before-first-report rules: docs/diagnose.md
// ("Re-simulation").
// Left out: the rig's own errors (fixture levelling, table wobble, the chamber air's difference
// from its controller's probe, the test set's pressure error), the firmware (rows in raw mode 0).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "hil/recording/recording_files.h"

namespace adahrs::rig_sim {

struct ReplayOptions {
  uint64_t noise_seed = 1;  ///< each unit's noise stream is drawn from this and its serial
  /// Each unit's noise stream as the rig drew it, from the unit file's "seed" (a truth file has
  /// it): with the file the rig ran, a recording of one row per frame is reproduced bit for bit.
  bool noise_from_unit_file = false;
  hil::RecordingStorage storage = hil::RecordingStorage::kGzip;  ///< of the written CSVs
};

struct ReplaySummary {
  uint64_t imu_rows = 0;
  uint64_t ads_rows = 0;
  std::vector<std::string> replayed;  ///< serials replayed
  std::vector<std::string>
      skipped;  ///< serials of the recording without a unit file (rows not written)
};

/// Replays `run_dir` into `out_dir` (which must not exist yet) with one unit file per unit to
/// replay. Writes meta.json (the recording's, with "replay": {of, noise, unit_files} and only
/// the replayed units), imu.csv, ads.csv and truth/<serial>.json (the unit file's content).
/// Throws common::ParamError for a bad unit file, hil::RecordingError for a bad recording, and
/// std::runtime_error naming the file for a unit file whose serial the recording does not hold,
/// two files of one serial, an existing `out_dir`, or a unit's time going backwards.
ReplaySummary ReplayRecording(const std::filesystem::path& run_dir,
                              const std::vector<std::filesystem::path>& unit_files,
                              const std::filesystem::path& out_dir,
                              const ReplayOptions& options = {});

}  // namespace adahrs::rig_sim
