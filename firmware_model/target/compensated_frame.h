// Raw input frames and compensated output frames of the IM3 and ADS compensators.
//
// Every compensated value is an int32 Q31 mantissa of a power-of-two full scale,
//   value = word * 2^(exponent - 31),  |value| < 2^exponent,
// with the exponents of imu_constants.h / ads_constants.h. The protocol carries them opaquely.
//
// IMU, 9 values per frame, by mode (slot: quantity, unit, full scale, LSB):
//   RAW                0..5  U = T1/T2 - 0.5 of az1 ax1 ay1 az2 ax2 ay2, duty, +-1, 2^-31
//                      6..8  gyro counts gx gy gz, counts, +-2^23, 2^-8 count
//   THERMAL            as RAW, after T = U - xi(t) (Eq. 4-5)
//   SENSOR_CALIBRATED  0..5  (T - O)/S per accel channel, g along the channel's body axis (both
//                            channels of an axis read +1 g with that axis up), +-16 g, 2^-27 g
//                      6..8  Eq. 23 rate of gx gy gz, deg/s, +-256 deg/s, 2^-23 deg/s
//   FULLY_CALIBRATED   0..2  A = CA * Ca (Eq. 26), x y z, m/s^2, +-256 m/s^2, 2^-23 m/s^2, where
//                            Ca_axis = (ch1 + ch2)/2, the mean of the axis's two opposite-polarity
//                            channels after (T - O)/S (their independent errors average down)
//                      3..5  G = CG * Cg (Eq. 29), x y z, deg/s, +-256 deg/s, 2^-23 deg/s
//                      6..8  (ch1 - ch2)/2 per axis x y z in g, +-16 g: the pair disagreement, a
//                            health monitor (zero for a perfect calibration)
// ADS, 2 values per frame:
//   RAW                0 ps code, 1 pt code (raw ADS1254 codes, exponent 31)
//   SURFACE            0 altitude, ft, +-65,536 ft, 2^-15 ft; 1 airspeed, kt, +-512 kt, 2^-22 kt
// Status flags report saturation: an input outside its normalisation range or a result clipped
// to full scale. The value is then the saturated one, never a wrapped one.
#ifndef ADAHRS_FW_COMPENSATED_FRAME_H
#define ADAHRS_FW_COMPENSATED_FRAME_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/// IMU output modes; values equal the protocol's mode byte (docs/unit-protocol.md section 4.1).
typedef enum {
  FW_IMU_MODE_RAW = 0x00,
  FW_IMU_MODE_THERMAL = 0x01,
  FW_IMU_MODE_SENSOR_CALIBRATED = 0x02,
  FW_IMU_MODE_FULLY_CALIBRATED = 0x03
} FwImuMode;

/// ADS output modes; values equal the protocol's mode byte (docs/unit-protocol.md section 5.1).
typedef enum { FW_ADS_MODE_RAW = 0x00, FW_ADS_MODE_SURFACE = 0x01 } FwAdsMode;

/// One IMU sample as the dsPIC acquires it (physics.md sections 1.3, 2).
typedef struct {
  uint16_t t1_cnt[6];    ///< ADXL210E high time, timer counts, az1 ax1 ay1 az2 ax2 ay2
  uint16_t t2_cnt[6];    ///< ADXL210E period, timer counts (t1 < t2)
  int32_t gyro_cnt[3];   ///< gx gy gz: 16 summed 19-bit conversions (null ~4.2e6)
  uint16_t temp_cnt[3];  ///< gyro temperature sensors: 16 summed 12-bit conversions
} FwImuRawFrame;

/// One ADS sample: ADS1254 24-bit two's-complement codes, sign-extended to int32.
typedef struct {
  int32_t ps_cnt;
  int32_t pt_cnt;
  int32_t ps_bridge_cnt;  ///< static bridge voltage (its temperature)
  int32_t pt_bridge_cnt;  ///< pitot bridge voltage (its temperature)
  int32_t oat_cnt;        ///< carried, not compensated here
} FwAdsRawFrame;

#define FW_IMU_OUTPUT_VALUES 9u
#define FW_ADS_OUTPUT_VALUES 2u

/// Status bits of a compensated frame.
#define FW_FLAG_INPUT_SATURATED ((uint16_t)0x0001u)   ///< an input fell outside its normalisation
#define FW_FLAG_OUTPUT_SATURATED ((uint16_t)0x0002u)  ///< a stage result was clipped to full scale
#define FW_FLAG_BAD_DUTY ((uint16_t)0x0004u)          ///< t1 >= t2 or t2 == 0: U set to +full scale

typedef struct {
  int32_t value[FW_IMU_OUTPUT_VALUES];
  uint16_t flags;
} FwImuCompensatedFrame;

typedef struct {
  int32_t value[FW_ADS_OUTPUT_VALUES];
  uint16_t flags;
} FwAdsCompensatedFrame;

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_COMPENSATED_FRAME_H
