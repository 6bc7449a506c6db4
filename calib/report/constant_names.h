// The engineer's name of an IMU constant from its JSON path in constants.json: the channel (az1 ..
// gz, docs/frames-and-units.md), the thermometer (tx, ty, tz) or the axes (x, y, z) it belongs
// to, and the term ("thermal gx k1", "accel ay2 scale_duty_per_g", "CA[y][z]"). ADS paths and any
// path it does not know are returned as they are.
#pragma once

#include <string>

namespace adahrs::calib {

/// "/thermal/6/k/1" -> "thermal gx k1"; "/ca_mps2_per_g/1/2" -> "CA[y][z]".
std::string ImuConstantName(const std::string& json_path);

}  // namespace adahrs::calib
