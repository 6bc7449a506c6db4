// Payloads of the 100 Hz data packets (docs/unit-protocol.md §4 IMU, §5 ADS): typed structs and
// their little-endian byte layout.
//
// IMU: the six ADXL210E channels az1 ax1 ay1 az2 ax2 ay2 as (T1, T2) input-capture ticks of the
// dsPIC's 16-bit timer, the three ADXRS150 rate counts (16 summed 19-bit conversions), the three
// gyro temperature counts (16 summed 12-bit conversions), the output mode, and in compensated
// modes the nine int32 values and the status flags of an FwImuCompensatedFrame, whose meaning and
// LSB per mode compensated_frame.h defines; the codec carries them opaquely.
// ADS: the ADS1254 codes of the static (ps) and pitot (pt) bridges, of their bridge voltages
// (sensor temperature) and of the OAT input, the mode, and in surface mode altitude, airspeed and
// flags (an FwAdsCompensatedFrame).
// Raw inputs use the compensator's own frame types (compensated_frame.h), so a unit model passes
// what it acquired and computed straight to the encoder.
#ifndef ADAHRS_FW_DATA_PAYLOADS_H
#define ADAHRS_FW_DATA_PAYLOADS_H

#include <stdbool.h>
#include <stdint.h>

#include "compensated_frame.h"
#include "unit_protocol.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  FwImuRawFrame raw;
  FwImuMode mode;
  /// Carried unless mode is RAW; all zero after decoding a raw-mode packet.
  FwImuCompensatedFrame compensated;
} FwImuDataPayload;

typedef struct {
  FwAdsRawFrame raw;
  FwAdsMode mode;
  /// Carried unless mode is RAW; all zero after decoding a raw-mode packet.
  FwAdsCompensatedFrame compensated;
} FwAdsDataPayload;

/// Payload length of an IMU packet in `mode` (43 raw, 81 otherwise).
uint8_t fw_imu_payload_bytes(FwImuMode mode);
/// Payload length of an ADS packet in `mode` (21 raw, 31 surface).
uint8_t fw_ads_payload_bytes(FwAdsMode mode);

/// True for a mode byte defined for the unit kind.
bool fw_is_imu_mode_byte(uint8_t mode);
bool fw_is_ads_mode_byte(uint8_t mode);

/// Writes the payload; returns its length, or 0 if `capacity` is too small or the mode unknown.
uint8_t fw_encode_imu_payload(const FwImuDataPayload* data, uint8_t* out, uint8_t capacity);
uint8_t fw_encode_ads_payload(const FwAdsDataPayload* data, uint8_t* out, uint8_t capacity);

/// Reads a payload; false (and *data untouched) if the mode byte is unknown or the length does
/// not match the mode.
bool fw_decode_imu_payload(const uint8_t* payload, uint8_t length, FwImuDataPayload* data);
bool fw_decode_ads_payload(const uint8_t* payload, uint8_t length, FwAdsDataPayload* data);

/// Encodes a complete IMU/ADS data frame; returns its length or 0 (see fw_encode_frame).
uint16_t fw_encode_imu_data_frame(const FwImuDataPayload* data,
                                  uint8_t sequence,
                                  uint8_t tag,
                                  uint8_t* out,
                                  uint16_t out_capacity);
uint16_t fw_encode_ads_data_frame(const FwAdsDataPayload* data,
                                  uint8_t sequence,
                                  uint8_t tag,
                                  uint8_t* out,
                                  uint16_t out_capacity);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_DATA_PAYLOADS_H
