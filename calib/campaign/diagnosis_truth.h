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

#include "calib/diagnosis/imu_diagnosis.h"

namespace adahrs::calib {

struct DiagnosisTruthLine {
  std::string serial;
  std::string effect;
  std::string channel;
  bool found = false;
  std::string text;  ///< "found 0.21 +- 0.03 dps/g along -X; truth -0.20 dps/g", or why not found
};

/// One line per (unit, channel, effect) the truth has and the nominal model lacks, or that the
/// diagnosis reported. Throws sensor_sim::ParamError naming a missing or malformed truth file.
std::vector<DiagnosisTruthLine> CompareDiagnosisWithTruth(const std::vector<UnitDiagnosis>& units,
                                                          const std::filesystem::path& truth_dir);

}  // namespace adahrs::calib
