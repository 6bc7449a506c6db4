// The reference method's calibration stages (reference-method.md, Method 2-5): thermal drift,
// then the sensors (six-position offsets and scales, gyro cubics) on mode-1 output, then the
// cross-axis matrices on mode-2 output; the mode a unit streams in once a file fitted up to a stage
// is downloaded. A staged fit is the reference method's, format 2.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "firmware_model/unit_firmware.h"

namespace adahrs::calib {

enum class ImuStage : uint8_t { kThermal, kSensor, kCrossAxis };

inline constexpr ImuStage kImuStages[] = {
    ImuStage::kThermal, ImuStage::kSensor, ImuStage::kCrossAxis};

/// "thermal", "sensor", "cross_axis".
std::string_view ImuStageName(ImuStage stage);
/// The stage named `name`, or nullopt.
std::optional<ImuStage> ParseImuStage(std::string_view name);
/// The stages up to and including `stage`, in order: what a file fitted at `stage` holds.
std::vector<ImuStage> StagesThrough(ImuStage stage);
/// The mode a unit runs once `stage` is downloaded: kThermal, kSensorCalibrated,
/// kFullyCalibrated.
firmware_model::ImuCompensationMode ModeAfter(ImuStage stage);

}  // namespace adahrs::calib
