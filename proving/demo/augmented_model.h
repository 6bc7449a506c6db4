// The diagnosis written back into the simulator's unit schema (`adahrs diagnose --model`,
// OUT/model.json): a unit file of the rig's truth schema ({kind, model_profile, params},
// docs/rig.md) with each finding's effect switched on at its fitted value, so `adahrs rig` can run
// the unit the recording showed. The diagnosis is made without the simulator (calib/diagnosis);
// this file only reads and writes the schema, through sensor_sim's parameter structs, whose range
// checks refuse a value no part could have. Mapping (docs/diagnose.md "The augmented model"):
//   gyro_g_sensitivity   B components into the gyro package: g_G = R_GB g_B
//   scale_factor_tempco  the axis's or gyro's sensitivity tc1, tc2 (tc3 0)
//   die_thermal_lag      the accelerometer die's time constant: the thermometer die's plus the
//   delay
//                        (weighted mean of the chip's two channels)
//   pressure_hysteresis, thermal_hysteresis   the bridge's h = 2 half loop / full scale, its span
// Left out, each listed in `not_applied` with the reason: effects with no parameter of that form
// in the schema (thermal hysteresis and warm-up on IMU channels, nonlinearity beyond the modelled
// order, generic channel findings).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "diagnosis/diagnosis_output.h"
#include "diagnosis/imu_diagnosis.h"

namespace adahrs::proving {

struct AugmentedModel {
  nlohmann::json model;  ///< the unit file: kind, model_profile, params
  std::vector<std::string>
      applied;  ///< "pitot_bridge.pressure_hysteresis_pct_fso = 0.072 (pt pressure_hysteresis)"
  std::vector<std::string> not_applied;  ///< finding and reason
};

/// `base_file` is a unit file of the truth schema whose serial is `diagnosis.serial`. Throws
/// common::ParamError naming the file and JSON path when it is not one, or when the result
/// would be out of the schema's ranges.
AugmentedModel AugmentUnitModel(const diagnosis::UnitDiagnosis& diagnosis,
                                const std::filesystem::path& base_file);

/// The unit of `run` whose serial is the base file's, augmented and written as `out_dir`/model.json
/// (atomically). Throws common::ParamError when no diagnosed unit is the base file's.
AugmentedModel WriteAugmentedModel(const diagnosis::DiagnosisRun& run,
                                   const std::filesystem::path& base_file,
                                   const std::filesystem::path& out_dir);

}  // namespace adahrs::proving
