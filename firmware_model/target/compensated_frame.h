// Raw input frames and compensated output frames of the IM3 and ADS compensators. Every
// compensated value is an int32 Q31 mantissa of a power-of-two full scale,
// value = word * 2^(exponent - 31), |value| < 2^exponent, with the exponents of imu_constants.h /
// ads_constants.h; the protocol carries them opaquely.
// IMU, 9 values by mode: RAW and THERMAL slots 0..5 duty U = T1/T2 - 0.5 (THERMAL after
// T = U - xi, Eq. 4-5), 6..8 gyro counts; SENSOR_CALIBRATED 0..5 g along each channel's body axis
// (Eq. 12), 6..8 deg/s (Eq. 23); FULLY_CALIBRATED 0..2 A in m/s^2 (Eq. 26, from the pair mean
// Ca_axis = (ch1 + ch2)/2), 3..5 G in deg/s (Eq. 29), 6..8 the pair disagreement (ch1 - ch2)/2
// in g, a health monitor. ADS, 2 values: RAW the ps and pt codes (exponent 31); SURFACE altitude
// in ft and airspeed in kt. Frames: body axes x y z of the unit.
// Full scales and LSBs per slot: docs/firmware-compensator.md ("Number formats") and
// docs/recording-format.md ("imu.csv"). Status flags report saturation (an input outside its
// normalisation range or a result clipped to full scale): the value is then the saturated one,
// never a wrapped one.
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
