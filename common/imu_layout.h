// The nominal layout of the IM³ inertial cube and its one channel table: the nine channels in the
// order the unit reports them, the body axis and sign each senses, the TEMP sensor beside each,
// and the nominal package rotations. Misalignment of a real unit is not here (sensor_sim's
// Im3Geometry draws it; the pipeline fits it).
//
// Frames (docs/frames-and-units.md): B unit case, C_k accelerometer chip k's package frame (x_C,
// y_C sensitive), G_k gyro k's package frame (z_G sensitive); f_C = R_CB · f_B.
// Mounting (reference-method.md "The unit"): chip 0 x_C = −z_B (az1), y_C = −x_B (ax1); chip 1
// x_C = +y_B (ay1), y_C = +z_B (az2); chip 2 x_C = +x_B (ax2), y_C = −y_B (ay2); gyros gx gy gz
// with z_G along +x_B, +y_B, +z_B.
#pragma once

#include <array>

#include <Eigen/Dense>

namespace adahrs::common {

inline constexpr int kImuChannelCount = 9;
inline constexpr int kAccelChannelCount = 6;

/// One channel of the IMU: what it is called, what it senses and which thermometer sits beside it.
struct ImuChannel {
  const char* name;
  int axis;          ///< body axis sensed: 0 x_B, 1 y_B, 2 z_B
  int sign;          ///< sign of the nominal sensitivity along that axis
  int thermometer;   ///< TEMP sensor nearest the package (the firmware's thermal assignment)
  int package;       ///< accelerometer chip or gyro package, 0..2
  int package_axis;  ///< accelerometers: 0 x_C, 1 y_C; gyros: 2 (z_G)
  bool gyro;
};

/// The channel table, in the unit's order: az1 ax1 ay1 az2 ax2 ay2 gx gy gz.
inline constexpr std::array<ImuChannel, kImuChannelCount> kImuChannels = {{
    {"az1", 2, -1, 0, 0, 0, false},
    {"ax1", 0, -1, 0, 0, 1, false},
    {"ay1", 1, +1, 1, 1, 0, false},
    {"az2", 2, +1, 1, 1, 1, false},
    {"ax2", 0, +1, 2, 2, 0, false},
    {"ay2", 1, -1, 2, 2, 1, false},
    {"gx", 0, +1, 0, 0, 2, true},
    {"gy", 1, +1, 1, 1, 2, true},
    {"gz", 2, +1, 2, 2, 2, true},
}};

inline constexpr std::array<const char*, kImuChannelCount> kImuChannelNames = {
    "az1", "ax1", "ay1", "az2", "ax2", "ay2", "gx", "gy", "gz"};
inline constexpr std::array<const char*, kAccelChannelCount> kAccelChannelNames = {
    "az1", "ax1", "ay1", "az2", "ax2", "ay2"};
inline constexpr std::array<const char*, 3> kGyroChannelNames = {"gx", "gy", "gz"};

inline constexpr bool IsGyroChannel(int channel) { return channel >= kAccelChannelCount; }

/// Nominal R_CB of accelerometer chip `chip` (0..2); throws std::out_of_range otherwise.
Eigen::Matrix3d NominalR_CB(int chip);
/// Nominal R_GB of gyro package `gyro` (0..2); throws std::out_of_range otherwise.
Eigen::Matrix3d NominalR_GB(int gyro);

}  // namespace adahrs::common
