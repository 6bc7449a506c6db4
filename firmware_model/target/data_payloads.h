// Payloads of the 100 Hz data packets (docs/unit-protocol.md §4 IMU, §5 ADS): typed structs and
// their little-endian byte layout.
//
// IMU: the six ADXL210E channels az1 ax1 ay1 az2 ax2 ay2 as (T1, T2) input-capture ticks of the
// dsPIC's 16-bit timer, the three ADXRS150 rate counts (16 summed 19-bit conversions), the three
// gyro temperature counts (16 summed 12-bit conversions), the output mode, and in compensated
// modes nine int32 values whose meaning and LSB per mode the compensator defines
// (target/compensated_frame.h); the codec carries them opaquely.
// ADS: the ADS1254 codes of the static (ps) and pitot (pt) bridges, of their bridge voltages
// (sensor temperature), of the OAT input, the mode, and in surface mode altitude and airspeed.
// Not modelled: any status/health bits (the reference unit's packet has none documented).
#pragma once

#include <cstdint>

#include "firmware_model/target/unit_protocol.h"

namespace adahrs::firmware_model {

/// One accelerometer channel's duty-cycle capture: T1 (high time) and T2 (period), timer ticks.
struct AccelCapture {
  uint16_t t1_cnt;
  uint16_t t2_cnt;
};

struct ImuDataPayload {
  AccelCapture accel[kImuAccelChannels];     ///< az1 ax1 ay1 az2 ax2 ay2
  int32_t gyro_cnt[kImuGyroChannels];        ///< gx gy gz
  uint16_t temp_cnt[kImuTempChannels];       ///< tx ty tz
  ImuMode mode;
  /// Present unless mode is raw (then zero); LSB per mode in target/compensated_frame.h.
  int32_t compensated_lsb[kImuCompensatedValues];
};

struct AdsDataPayload {
  int32_t ps_cnt;          ///< static bridge, 24-bit ADS1254 code, sign-extended
  int32_t pt_cnt;          ///< pitot bridge
  int32_t ps_bridge_cnt;   ///< static bridge voltage (sensor temperature)
  int32_t pt_bridge_cnt;   ///< pitot bridge voltage
  int32_t oat_cnt;         ///< outside air temperature input
  AdsMode mode;
  /// Altitude then airspeed, present unless mode is raw (then zero); LSB in compensated_frame.h.
  int32_t compensated_lsb[kAdsCompensatedValues];
};

/// Payload length of an IMU packet in `mode` (43 raw, 79 otherwise).
uint8_t ImuPayloadBytes(ImuMode mode);
/// Payload length of an ADS packet in `mode` (21 raw, 29 surface).
uint8_t AdsPayloadBytes(AdsMode mode);

/// Writes the payload; returns its length, or 0 if `capacity` is too small or the mode unknown.
uint8_t EncodeImuPayload(const ImuDataPayload& data, uint8_t* out, uint8_t capacity);
uint8_t EncodeAdsPayload(const AdsDataPayload& data, uint8_t* out, uint8_t capacity);

/// Reads a payload; false (and *data untouched) if the mode byte is unknown or the length does
/// not match the mode.
bool DecodeImuPayload(const uint8_t* payload, uint8_t length, ImuDataPayload* data);
bool DecodeAdsPayload(const uint8_t* payload, uint8_t length, AdsDataPayload* data);

/// Encodes a complete IMU/ADS data frame; returns its length or 0 (see EncodeFrame).
uint16_t EncodeImuDataFrame(const ImuDataPayload& data, uint8_t sequence, uint8_t tag, uint8_t* out,
                            uint16_t out_capacity);
uint16_t EncodeAdsDataFrame(const AdsDataPayload& data, uint8_t sequence, uint8_t tag, uint8_t* out,
                            uint16_t out_capacity);

}  // namespace adahrs::firmware_model
