// Golden vectors for the target compensators: constants as the maintenance port's int16 block
// words, raw input frames, and the bit-exact outputs, flags and cycle counts of every mode, in one
// JSON document (tests/firmware_model/data/compensator_golden.json). A target build replays it by
// writing each block with Imu/AdsConstantsWriteBlock, running each frame, and comparing words.
// The ADS frames run in order from fresh hysteresis operators (ads_compensator.h), so a replay
// checks the operators' memory as well as each frame.
// The IMU blocks are 0x01..0x0F for a format-2 set, 0x01..0x1B when the format-3 stages are on.
// Layout: {"format": 1, "imu": {"blocks": [{"id", "words"}], "frames": [{"t1_cnt", "t2_cnt",
// "gyro_cnt", "temp_cnt", "modes": [{"mode", "value", "flags", "cycles"}]}]}, "ads": {...
// "frames": [{"ps_code", "pt_code", "ps_bridge_code", "pt_bridge_code", "oat_code", "modes"}]}}.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "firmware_model/unit_firmware.h"

namespace adahrs::firmware_model {

/// Runs every frame in every mode and records inputs, constants (as block words) and outputs.
nlohmann::json MakeCompensatorGolden(const ImuConstants& imu,
                                     const AdsConstants& ads,
                                     const std::vector<ImuRawFrame>& imu_frames,
                                     const std::vector<AdsRawFrame>& ads_frames);

/// Replays a golden document; returns "" if every output word, flag and cycle count matches,
/// otherwise a description of the first mismatch (frame, mode, slot, expected, got).
std::string ReplayCompensatorGolden(const nlohmann::json& golden);

}  // namespace adahrs::firmware_model
