// Raw input frames and compensated output frames of the IM3 and ADS compensators.
//
// Every compensated value is an int32 Q31 mantissa of a power-of-two full scale,
//   value = word * 2^(exponent - 31),  |value| < 2^exponent,
// with the exponents of imu_constants.h / ads_constants.h. The protocol carries them opaquely.
//
// IMU, 9 values per frame, by mode (slot: quantity, unit, full scale, LSB):
//   kRaw             0..5  U = T1/T2 - 0.5 of az1 ax1 ay1 az2 ax2 ay2, duty, +-1, 2^-31
//                    6..8  gyro counts gx gy gz, counts, +-2^23, 2^-8 count
//   kThermal         as kRaw, after T = U - xi(t) (Eq. 4-5)
//   kSensorCalibrated 0..5 (T - O)/S per accel channel, g along the channel's body axis (both
//                          channels of an axis read +1 g with that axis up), +-16 g, 2^-27 g
//                    6..8  Eq. 23 rate of gx gy gz, deg/s, +-256 deg/s, 2^-23 deg/s
//   kFullyCalibrated 0..2  A = CA * Ca (Eq. 26), x y z, m/s^2, +-256 m/s^2, 2^-23 m/s^2, where
//                          Ca_axis = (ch1 + ch2)/2, the mean of the axis's two opposite-polarity
//                          channels after (T - O)/S (their independent errors average down)
//                    3..5  G = CG * Cg (Eq. 29), x y z, deg/s, +-256 deg/s, 2^-23 deg/s
//                    6..8  (ch1 - ch2)/2 per axis x y z in g, +-16 g: the pair disagreement, a
//                          health monitor (zero for a perfect calibration)
// ADS, 2 values per frame:
//   kRaw             0 ps code, 1 pt code (raw ADS1254 codes, exponent 31)
//   kSurface         0 altitude, ft, +-65,536 ft, 2^-15 ft; 1 airspeed, kt, +-512 kt, 2^-22 kt
// Status flags report saturation: an input outside its normalisation range or a result clipped
// to full scale. The value is then the saturated one, never a wrapped one.
#pragma once

#include <cstdint>

namespace adahrs::firmware_model {

/// IMU output modes; values equal the protocol's mode byte (docs/unit-protocol.md section 4.1).
enum class ImuCompensationMode : uint8_t {
  kRaw = 0x00,
  kThermal = 0x01,
  kSensorCalibrated = 0x02,
  kFullyCalibrated = 0x03,
};

/// ADS output modes; values equal the protocol's mode byte (docs/unit-protocol.md section 5.1).
enum class AdsCompensationMode : uint8_t {
  kRaw = 0x00,
  kSurface = 0x01,
};

/// One IMU sample as the dsPIC acquires it (physics.md sections 1.3, 2).
struct ImuRawFrame {
  uint16_t t1_cnt[6];    ///< ADXL210E high time, timer counts, az1 ax1 ay1 az2 ax2 ay2
  uint16_t t2_cnt[6];    ///< ADXL210E period, timer counts (t1 < t2)
  int32_t gyro_cnt[3];   ///< gx gy gz: 16 summed 19-bit conversions (null ~4.2e6)
  uint16_t temp_cnt[3];  ///< gyro temperature sensors: 16 summed 12-bit conversions
};

/// One ADS sample: ADS1254 24-bit two's-complement codes, sign-extended to int32.
struct AdsRawFrame {
  int32_t ps_cnt;
  int32_t pt_cnt;
  int32_t ps_bridge_cnt;  ///< static bridge voltage (its temperature)
  int32_t pt_bridge_cnt;  ///< pitot bridge voltage (its temperature)
  int32_t oat_cnt;        ///< carried, not compensated here
};

inline constexpr uint8_t kImuOutputValues = 9;
inline constexpr uint8_t kAdsOutputValues = 2;

/// Status bits of a compensated frame.
enum CompensationFlag : uint16_t {
  kFlagInputSaturated = 0x0001,   ///< an input fell outside its normalisation range
  kFlagOutputSaturated = 0x0002,  ///< a stage result was clipped to its full scale
  kFlagBadDuty = 0x0004,          ///< t1 >= t2 or t2 == 0: duty undefined, U set to +-full scale
};

struct ImuCompensatedFrame {
  int32_t value[kImuOutputValues];
  uint16_t flags;
};

struct AdsCompensatedFrame {
  int32_t value[kAdsOutputValues];
  uint16_t flags;
};

}  // namespace adahrs::firmware_model
