// IMU calibration strategies selectable by name in a strategy file
// (docs/calibration-strategies.md), and the fit of recordings into one constants.json per unit.
//
//   {"format": "adahrs-imu-strategy", "format_version": 1, "strategy": "reference" | "joint",
//    "thermal_order": "auto" | 0 | 1 | 2,     (joint only; "auto" = held-out choice, default)
//    "thermal_band_width_cnt": 110,            (optional, both)
//    "firmware_format": 2 | 3}                 (joint only; 3 fits the scale-temperature terms)
// or an external program's strategy (docs/strategies-external.md):
//   {"format": "adahrs-imu-strategy", "format_version": 1, "strategy": NAME,
//    "program": ["python3", "my_fit.py"], "timeout_s": 600, "firmware_format": 2 | 3,
//    "inputs": {...}, "options": {...}}
//
// "reference" is the reference method exactly (imu_reference_fit.h); "joint" is the improved
// strategy (imu_joint_fit.h). The strict reader names the file and JSON path of a bad key.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "calib/constants/constants_file.h"
#include "calib/imu_calibration/external_strategy.h"

namespace adahrs::calib {

struct ImuStrategy {
  std::string name = "joint";        ///< "reference" or "joint"
  std::optional<int> thermal_order;  ///< joint: empty = chosen by held-out error
  double band_width_cnt = 110.0;
  bool estimate_gyro_wander = false;  ///< joint: the wander from the recording, else datasheet's
  bool format3 = false;               ///< joint: fit the firmware's format-3 terms too
  std::optional<ExternalImuProgram> external;  ///< set: a program fits (name is its name)

  /// The reference method exactly.
  static ImuStrategy Reference();
  /// The joint strategy for the firmware's format 2 (no scale-temperature terms).
  static ImuStrategy JointFormat2();
  /// The joint strategy for the firmware's format 3: what `adahrs fit` fits and the campaign
  /// downloads when no strategy is named.
  static ImuStrategy JointFormat3();
  /// Reads a strategy file; throws common::ParamError naming the file and JSON path.
  static ImuStrategy Load(const std::filesystem::path& path);
};

struct ImuUnitData;
struct ImuRunData;

/// The staged process (docs/campaign.md "The staged process"): fit `stage` alone with the
/// reference strategy; past the thermal stage the earlier stages come from the unit's file in
/// `base_dir` (`<serial>.json`, the previous stage's output).
struct ImuStageRequest {
  ImuStage stage = ImuStage::kThermal;
  std::filesystem::path base_dir;
};

/// The unit's file in `staged.base_dir`, which must hold every stage before `staged.stage`;
/// throws ImuInputError naming the file when it is missing, another unit's, or short of a stage.
ConstantsFile ReadStageBase(const std::string& serial, const ImuStageRequest& staged);

/// Fits one IMU of `data` (its gravity and provenance) with `strategy`, or one stage of it.
/// Throws DegenerateDesignError when the data cannot determine the constants, ImuInputError
/// when a staged fit's strategy is not the reference or its base is missing or unfit.
ConstantsFile FitImuUnit(const ImuUnitData& unit,
                         const ImuRunData& data,
                         const ImuStrategy& strategy,
                         const std::string& software_version,
                         const std::optional<ImuStageRequest>& staged = std::nullopt);

/// Fits every IMU of the runs with `strategy`; one constants file per unit, serial order.
/// Throws ImuInputError, hil::RecordingError or DegenerateDesignError with the reason.
std::vector<ConstantsFile> FitImuRuns(const std::vector<std::filesystem::path>& run_dirs,
                                      const ImuStrategy& strategy,
                                      const std::string& software_version,
                                      const std::optional<ImuStageRequest>& staged = std::nullopt);

}  // namespace adahrs::calib
