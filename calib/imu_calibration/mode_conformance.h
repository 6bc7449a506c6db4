// The unit's own compensation against the pipeline's model of it, on a recorded stream: for each
// row a unit sent in a compensated mode, the difference between each value it sent and
// firmware_model::ImuReference(constants, mode, the same row's raw counts), the constants being
// those the unit holds (the file last downloaded into it). The firmware team's check that the
// fixed-point code on the unit computes what the pipeline's double model computes, on whatever
// the unit met on the station; the golden vectors (firmware-compensator.md) check the same on
// chosen inputs.
// Units: each mode's (compensated_frame.h, docs/recording-format.md). Rows flagged saturated or
// with a bad duty (comp_flags) are counted apart and not compared: the model does not clamp.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "firmware_model/calibration_constants.h"

namespace adahrs::calib {

struct ChannelConformance {
  double max_abs_diff = 0.0;  ///< largest |unit - model|, in the mode's unit
  double rms_diff = 0.0;
};

struct ModeConformance {
  std::string serial;
  int mode = 0;              ///< the compensated mode compared (1, 2 or 3)
  int64_t rows = 0;          ///< rows compared
  int64_t flagged_rows = 0;  ///< rows in that mode with comp_flags set, not compared
  std::array<ChannelConformance, 9> channels{};  ///< comp0...comp8
  nlohmann::json ToJson() const;
};

/// Every unit of `run_dir` that has constants in `constants` (by serial) and rows in a
/// compensated mode, one entry per (unit, mode), in serial order. Throws hil::RecordingError
/// naming the file and line of a row the reader refuses.
std::vector<ModeConformance> CheckModeConformance(
    const std::filesystem::path& run_dir,
    const std::map<std::string, firmware_model::ImuCalibrationConstants>& constants);

/// One run's results, as mode_conformance.json lists them.
struct RunConformance {
  std::filesystem::path run_dir;
  std::vector<ModeConformance> units;
};

/// mode_conformance.json (docs/campaign.md "The staged process"): format
/// "adahrs-mode-conformance", version 1, one entry per run, unit and mode; written atomically.
void WriteModeConformance(const std::filesystem::path& path,
                          const std::vector<RunConformance>& runs);

}  // namespace adahrs::calib
