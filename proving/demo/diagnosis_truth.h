// The diagnosis stage of a campaign on a simulated rig: what `adahrs diagnose` found in the IMU
// calibration runs, set beside each unit's truth (`<truth_dir>/<serial>.json`, as
// truth_evaluation.h reads it). Only the campaign, which made the rig, knows the truth; the
// diagnosis itself never sees it.
// Truth of each vocabulary effect: die_thermal_lag, the accelerometer chip's die time constant
// minus that of the gyro die whose TEMP pin is its thermometer (when the truth has lag on);
// gyro_g_sensitivity, the package's g-sensitivity taken into B (R_GB' g_G); scale_factor_tempco,
// the first- and second-order sensitivity tempcos. Each effect the truth has on and the model
// leaves out, but the diagnosis did not report, is listed with the diagnosis's own reason
// (detection limit, or not excited by the recording).
// Left out: thermal hysteresis and warm-up (no truth term maps onto them one to one).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "diagnosis/diagnosis_output.h"
#include "diagnosis/imu_diagnosis.h"
#include "diagnosis/replay_comparison.h"

namespace adahrs::proving {

struct DiagnosisTruthLine {
  std::string serial;
  std::string effect;
  std::string channel;
  bool found = false;
  std::string
      text;  ///< "found 0.21 +- 0.03 deg/s/g along -X; truth -0.20 deg/s/g", or why not found
};

/// One line per (unit, channel, effect) the truth has and the nominal model lacks, or that the
/// diagnosis reported. Throws common::ParamError naming a missing or malformed truth file.
std::vector<DiagnosisTruthLine> CompareDiagnosisWithTruth(
    const std::vector<diagnosis::UnitDiagnosis>& units, const std::filesystem::path& truth_dir);

/// The truth file of `serial` with every effect the diagnosis vocabulary writes into a unit file
/// switched off (IMU: gyro g-sensitivity, scale factor vs temperature, each accelerometer die's own
/// lag, which takes its thermometer die's time constant; ADS: pressure and thermal hysteresis): a
/// unit model that lacks exactly what the diagnosis can add, from which the campaign's
/// re-simulation check starts. Throws common::ParamError naming a missing or malformed file.
nlohmann::json BaseModelFromTruth(const std::filesystem::path& truth_dir,
                                  const std::string& serial);

/// The campaign's held-out check of its diagnosis: per diagnosed unit, the base model
/// (BaseModelFromTruth) and the base with the findings switched on (WriteAugmentedModel), written
/// as `diagnosis_dir`/models/<serial>/{base,model}.json; each run of `check_runs` (runs the
/// diagnosis did not see) re-simulated with the bases and with the models of the units it holds
/// and compared with its recording -> `diagnosis_dir`/replay_check.json, replay_check.html. The
/// re-simulated runs, the size of their recordings, are removed once compared.
std::vector<diagnosis::ReplayComparison> CheckDiagnosisByReplay(
    const diagnosis::DiagnosisRun& diagnosed,
    const std::filesystem::path& truth_dir,
    const std::filesystem::path& diagnosis_dir,
    const std::vector<std::filesystem::path>& check_runs,
    const diagnosis::ReplayFunction& replay);

}  // namespace adahrs::proving
