// Payloads of the 100 Hz data packets (docs/unit-protocol.md §4 IMU, §5 ADS): typed structs and
// their little-endian byte layout.
//
// IMU: the six ADXL210E channels az1 ax1 ay1 az2 ax2 ay2 as (T1, T2) input-capture ticks of the
// dsPIC's 16-bit timer, the three ADXRS150 rate counts (16 summed 19-bit conversions), the three
// gyro temperature counts (16 summed 12-bit conversions), the output mode, and in compensated
// modes the nine int32 values and the status flags of an ImuCompensatedFrame, whose meaning and
// LSB per mode compensated_frame.h defines; the codec carries them opaquely.
// ADS: the ADS1254 codes of the static (ps) and pitot (pt) bridges, of their bridge voltages
// (sensor temperature) and of the OAT input, the mode, and in surface mode altitude, airspeed and
// flags (an AdsCompensatedFrame).
// Raw inputs use the compensator's own frame types (compensated_frame.h), so a unit model passes
// what it acquired and computed straight to the encoder.
#pragma once

#include <cstdint>

#include "firmware_model/target/compensated_frame.h"
#include "firmware_model/target/unit_protocol.h"

namespace adahrs::firmware_model {

struct ImuDataPayload {
  ImuRawFrame raw;
  ImuCompensationMode mode;
  /// Carried unless mode is kRaw; all zero after decoding a raw-mode packet.
  ImuCompensatedFrame compensated;
};

struct AdsDataPayload {
  AdsRawFrame raw;
  AdsCompensationMode mode;
  /// Carried unless mode is kRaw; all zero after decoding a raw-mode packet.
  AdsCompensatedFrame compensated;
};

/// Payload length of an IMU packet in `mode` (43 raw, 81 otherwise).
uint8_t ImuPayloadBytes(ImuCompensationMode mode);
/// Payload length of an ADS packet in `mode` (21 raw, 31 surface).
uint8_t AdsPayloadBytes(AdsCompensationMode mode);

/// True for a mode byte defined for the unit kind.
bool IsImuModeByte(uint8_t mode);
bool IsAdsModeByte(uint8_t mode);

/// Writes the payload; returns its length, or 0 if `capacity` is too small or the mode unknown.
uint8_t EncodeImuPayload(const ImuDataPayload& data, uint8_t* out, uint8_t capacity);
uint8_t EncodeAdsPayload(const AdsDataPayload& data, uint8_t* out, uint8_t capacity);

/// Reads a payload; false (and *data untouched) if the mode byte is unknown or the length does
/// not match the mode.
bool DecodeImuPayload(const uint8_t* payload, uint8_t length, ImuDataPayload* data);
bool DecodeAdsPayload(const uint8_t* payload, uint8_t length, AdsDataPayload* data);

/// Encodes a complete IMU/ADS data frame; returns its length or 0 (see EncodeFrame).
uint16_t EncodeImuDataFrame(
    const ImuDataPayload& data, uint8_t sequence, uint8_t tag, uint8_t* out, uint16_t out_capacity);
uint16_t EncodeAdsDataFrame(
    const AdsDataPayload& data, uint8_t sequence, uint8_t tag, uint8_t* out, uint16_t out_capacity);

}  // namespace adahrs::firmware_model
