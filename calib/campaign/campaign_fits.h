// The fitting stage of a calibration campaign: recordings in, one constants.json per unit out
// (constants_file.h, docs/constants-file.md), written to `<fit_dir>/<serial>.json`.
//   IMU: FitImuRuns (imu_strategy.h) over the thermal and sensor-calibration runs together, with
//        the strategy given (the reference method or the improved joint fit);
//   ADS: a 10-term cubic strategy by name (reference_ads_strategy.h, tolerance_ads_strategy.h) on
//        the calibration points of each ADS unit of the run (ads_calibration_points.h); provenance
//        is the run's RecordingSha256 and its sequence name.
// Errors pass through from the strategies (ImuInputError, DegenerateDesignError, RecordingError,
// each naming the run, step, unit, line or column).
// Left out: choosing between strategies (the campaign decides which fit it downloads).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "calib/constants/constants_file.h"
#include "calib/imu_calibration/imu_strategy.h"

namespace adahrs::calib {

struct WrittenConstants {
  std::filesystem::path path;
  ConstantsFile file;
  std::vector<std::string> log;  ///< an external strategy program's log lines
};

/// Fits every IMU of `run_dirs` with `strategy` and writes the files into `fit_dir`; nothing is
/// written unless every unit's fit succeeds. An external strategy's request and reply are kept
/// beside each file (`<serial>.request.json.gz`, `<serial>.reply.json.gz`).
std::vector<WrittenConstants> FitImuIntoDirectory(
    const std::vector<std::filesystem::path>& run_dirs,
    const ImuStrategy& strategy,
    const std::filesystem::path& fit_dir,
    const std::string& software_version,
    const std::optional<ImuStageRequest>& staged = std::nullopt);

/// Fits every ADS unit of `run_dir` with the ADS strategy named `strategy` (FitAdsStrategy:
/// "reference", "tolerance_minimax", "pressure_minimax" or "hysteresis_compensated") and writes
/// the files into `fit_dir`.
std::vector<WrittenConstants> FitAdsIntoDirectory(const std::filesystem::path& run_dir,
                                                  const std::string& strategy,
                                                  const std::filesystem::path& fit_dir,
                                                  const std::string& software_version);

/// The constants files a fit stage wrote into `fit_dir` (every `*.json` but evaluation.json, the
/// proving stage's), sorted by name; none if the directory does not exist.
std::vector<WrittenConstants> ReadFitDirectory(const std::filesystem::path& fit_dir);

}  // namespace adahrs::calib
