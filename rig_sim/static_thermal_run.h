// A static thermal run: a batch of simulated IMU units (fixed in one orientation) and ADS units
// (held at a constant static and impact pressure) in a thermal chamber that follows a profile of
// ramp-and-soak steps, logged in the recording format with each unit's truth beside it.
// This is the rig's world without the instruments' serial protocols: the chamber is the
// ChamberAir physics directly, the reference columns are what ideal instruments would report
// (chamber air as measured, the set pressures). Used by the demo and by thermal-calibration work
// until the virtual rig on pseudo-terminals drives the same units.
// Left out: the rate table (the units are static), fixture levelling error, the instruments'
// measurement errors (see rig_sim instrument models).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "hil/recording/recording_files.h"
#include "rig_sim/chamber_air.h"
#include "sensor_sim/model_profile.h"

namespace adahrs::rig_sim {

struct ThermalProfileStep {
  double target_c = 25.0;
  double ramp_c_per_min = 1.0;  ///< programmed set-point ramp toward the target
  double soak_s = 1800.0;       ///< guaranteed soak: counted only while the air is within the band
};

struct StaticThermalRunConfig {
  int imu_units = 4;
  int ads_units = 1;
  uint64_t seed = 1;
  sensor_sim::ModelProfile profile = sensor_sim::ModelProfile::kTruth;
  int orientation = 31;
  double latitude_deg = 45.0;  ///< station latitude, for local gravity
  double height_m = 0.0;       ///< station height, for local gravity
  double start_c = 25.0;
  double soak_band_c = 1.0;
  double ads_ps_pa = 101325.0;
  double ads_qc_pa = 1630.3;                                     ///< 100 kt CAS
  int log_every = 1;                                             ///< log every Nth packet (1 = all)
  hil::RecordingStorage storage = hil::RecordingStorage::kGzip;  ///< imu/ads CSVs, plain or gz
  std::vector<ThermalProfileStep> steps;
  ChamberAirParams chamber;

  /// The demo's profile: 25 → −20 °C, soak, → +65 °C, soak, → 25 °C at 2 °C/min, 20 min soaks.
  static StaticThermalRunConfig Demo();
};

struct StaticThermalRunSummary {
  double duration_s = 0.0;
  uint64_t frames = 0;  ///< 100 Hz frames simulated per unit
  uint64_t imu_rows = 0;
  uint64_t ads_rows = 0;
};

/// Runs the profile and writes `run_dir` (meta.json, imu.csv, ads.csv, truth/<serial>.json).
/// `on_step` is called at each step boundary with the step index and the simulated time.
StaticThermalRunSummary RunStaticThermal(
    const StaticThermalRunConfig& config,
    const std::filesystem::path& run_dir,
    const std::function<void(int step, double t_s)>& on_step = {});

}  // namespace adahrs::rig_sim
