#include "data_payloads.h"

#include "byte_order.h"
#include "imu_constants.h"
#include "packet_codec.h"

// Field offsets (docs/unit-protocol.md §4.2 and §5.2).
#define IMU_GYRO_OFFSET 24u
#define IMU_TEMP_OFFSET 36u
#define IMU_MODE_OFFSET 42u
#define IMU_VALUES_OFFSET 43u
#define IMU_FLAGS_OFFSET 79u
#define ADS_MODE_OFFSET 20u
#define ADS_VALUES_OFFSET 21u
#define ADS_FLAGS_OFFSET 29u

// The compensated values and their flags word, at their offsets in a payload.
static void PutCompensated(const int32_t* value,
                           uint8_t count,
                           uint16_t flags,
                           uint8_t values_offset,
                           uint8_t flags_offset,
                           uint8_t* out) {
  for (uint8_t i = 0u; i < count; ++i) {
    fw_put_i32_le(&out[values_offset + (4u * i)], value[i]);
  }
  fw_put_u16_le(&out[flags_offset], flags);
}

// Reads them back; a raw payload (`has_values` false) carries none and reads as zeros.
static void GetCompensated(const uint8_t* payload,
                           bool has_values,
                           uint8_t values_offset,
                           uint8_t flags_offset,
                           int32_t* value,
                           uint8_t count,
                           uint16_t* flags) {
  for (uint8_t i = 0u; i < count; ++i) {
    value[i] = has_values ? fw_get_i32_le(&payload[values_offset + (4u * i)]) : 0;
  }
  *flags = has_values ? fw_get_u16_le(&payload[flags_offset]) : 0u;
}

bool fw_is_imu_mode_byte(uint8_t mode) { return mode <= (uint8_t)FW_IMU_MODE_FULLY_CALIBRATED; }

bool fw_is_ads_mode_byte(uint8_t mode) { return mode <= (uint8_t)FW_ADS_MODE_SURFACE; }

uint8_t fw_imu_payload_bytes(FwImuMode mode) {
  return (mode == FW_IMU_MODE_RAW) ? (uint8_t)FW_IMU_RAW_PAYLOAD_BYTES
                                   : (uint8_t)FW_IMU_COMPENSATED_PAYLOAD_BYTES;
}

uint8_t fw_ads_payload_bytes(FwAdsMode mode) {
  return (mode == FW_ADS_MODE_RAW) ? (uint8_t)FW_ADS_RAW_PAYLOAD_BYTES
                                   : (uint8_t)FW_ADS_COMPENSATED_PAYLOAD_BYTES;
}

uint8_t fw_encode_imu_payload(const FwImuDataPayload* data, uint8_t* out, uint8_t capacity) {
  if (!fw_is_imu_mode_byte((uint8_t)data->mode)) {
    return 0u;
  }
  const uint8_t length = fw_imu_payload_bytes(data->mode);
  if (capacity < length) {
    return 0u;
  }
  for (uint8_t i = 0u; i < FW_ACCEL_CHANNELS; ++i) {
    fw_put_u16_le(&out[4u * i], data->raw.t1_cnt[i]);
    fw_put_u16_le(&out[(4u * i) + 2u], data->raw.t2_cnt[i]);
  }
  for (uint8_t i = 0u; i < FW_GYRO_CHANNELS; ++i) {
    fw_put_i32_le(&out[IMU_GYRO_OFFSET + (4u * i)], data->raw.gyro_cnt[i]);
  }
  for (uint8_t i = 0u; i < FW_TEMP_SENSORS; ++i) {
    fw_put_u16_le(&out[IMU_TEMP_OFFSET + (2u * i)], data->raw.temp_cnt[i]);
  }
  out[IMU_MODE_OFFSET] = (uint8_t)data->mode;
  if (data->mode != FW_IMU_MODE_RAW) {
    PutCompensated(data->compensated.value,
                   FW_IMU_OUTPUT_VALUES,
                   data->compensated.flags,
                   IMU_VALUES_OFFSET,
                   IMU_FLAGS_OFFSET,
                   out);
  }
  return length;
}

uint8_t fw_encode_ads_payload(const FwAdsDataPayload* data, uint8_t* out, uint8_t capacity) {
  if (!fw_is_ads_mode_byte((uint8_t)data->mode)) {
    return 0u;
  }
  const uint8_t length = fw_ads_payload_bytes(data->mode);
  if (capacity < length) {
    return 0u;
  }
  fw_put_i32_le(&out[0], data->raw.ps_cnt);
  fw_put_i32_le(&out[4], data->raw.pt_cnt);
  fw_put_i32_le(&out[8], data->raw.ps_bridge_cnt);
  fw_put_i32_le(&out[12], data->raw.pt_bridge_cnt);
  fw_put_i32_le(&out[16], data->raw.oat_cnt);
  out[ADS_MODE_OFFSET] = (uint8_t)data->mode;
  if (data->mode != FW_ADS_MODE_RAW) {
    PutCompensated(data->compensated.value,
                   FW_ADS_OUTPUT_VALUES,
                   data->compensated.flags,
                   ADS_VALUES_OFFSET,
                   ADS_FLAGS_OFFSET,
                   out);
  }
  return length;
}

bool fw_decode_imu_payload(const uint8_t* payload, uint8_t length, FwImuDataPayload* data) {
  if ((length < FW_IMU_RAW_PAYLOAD_BYTES) || !fw_is_imu_mode_byte(payload[IMU_MODE_OFFSET])) {
    return false;
  }
  const FwImuMode mode = (FwImuMode)payload[IMU_MODE_OFFSET];
  if (length != fw_imu_payload_bytes(mode)) {
    return false;
  }
  for (uint8_t i = 0u; i < FW_ACCEL_CHANNELS; ++i) {
    data->raw.t1_cnt[i] = fw_get_u16_le(&payload[4u * i]);
    data->raw.t2_cnt[i] = fw_get_u16_le(&payload[(4u * i) + 2u]);
  }
  for (uint8_t i = 0u; i < FW_GYRO_CHANNELS; ++i) {
    data->raw.gyro_cnt[i] = fw_get_i32_le(&payload[IMU_GYRO_OFFSET + (4u * i)]);
  }
  for (uint8_t i = 0u; i < FW_TEMP_SENSORS; ++i) {
    data->raw.temp_cnt[i] = fw_get_u16_le(&payload[IMU_TEMP_OFFSET + (2u * i)]);
  }
  data->mode = mode;
  GetCompensated(payload,
                 mode != FW_IMU_MODE_RAW,
                 IMU_VALUES_OFFSET,
                 IMU_FLAGS_OFFSET,
                 data->compensated.value,
                 FW_IMU_OUTPUT_VALUES,
                 &data->compensated.flags);
  return true;
}

bool fw_decode_ads_payload(const uint8_t* payload, uint8_t length, FwAdsDataPayload* data) {
  if ((length < FW_ADS_RAW_PAYLOAD_BYTES) || !fw_is_ads_mode_byte(payload[ADS_MODE_OFFSET])) {
    return false;
  }
  const FwAdsMode mode = (FwAdsMode)payload[ADS_MODE_OFFSET];
  if (length != fw_ads_payload_bytes(mode)) {
    return false;
  }
  data->raw.ps_cnt = fw_get_i32_le(&payload[0]);
  data->raw.pt_cnt = fw_get_i32_le(&payload[4]);
  data->raw.ps_bridge_cnt = fw_get_i32_le(&payload[8]);
  data->raw.pt_bridge_cnt = fw_get_i32_le(&payload[12]);
  data->raw.oat_cnt = fw_get_i32_le(&payload[16]);
  data->mode = mode;
  GetCompensated(payload,
                 mode != FW_ADS_MODE_RAW,
                 ADS_VALUES_OFFSET,
                 ADS_FLAGS_OFFSET,
                 data->compensated.value,
                 FW_ADS_OUTPUT_VALUES,
                 &data->compensated.flags);
  return true;
}

// Frames a payload an encoder wrote (`length` 0: the encoder refused it, and so does this).
static uint16_t FrameDataPayload(FwPacketType type,
                                 const uint8_t* payload,
                                 uint8_t length,
                                 uint8_t sequence,
                                 uint8_t tag,
                                 uint8_t* out,
                                 uint16_t out_capacity) {
  return (length == 0u)
             ? 0u
             : fw_encode_frame((uint8_t)type, sequence, tag, payload, length, out, out_capacity);
}

uint16_t fw_encode_imu_data_frame(const FwImuDataPayload* data,
                                  uint8_t sequence,
                                  uint8_t tag,
                                  uint8_t* out,
                                  uint16_t out_capacity) {
  uint8_t payload[FW_IMU_COMPENSATED_PAYLOAD_BYTES];
  const uint8_t length =
      fw_encode_imu_payload(data, payload, (uint8_t)FW_IMU_COMPENSATED_PAYLOAD_BYTES);
  return FrameDataPayload(FW_PACKET_IMU_DATA, payload, length, sequence, tag, out, out_capacity);
}

uint16_t fw_encode_ads_data_frame(const FwAdsDataPayload* data,
                                  uint8_t sequence,
                                  uint8_t tag,
                                  uint8_t* out,
                                  uint16_t out_capacity) {
  uint8_t payload[FW_ADS_COMPENSATED_PAYLOAD_BYTES];
  const uint8_t length =
      fw_encode_ads_payload(data, payload, (uint8_t)FW_ADS_COMPENSATED_PAYLOAD_BYTES);
  return FrameDataPayload(FW_PACKET_ADS_DATA, payload, length, sequence, tag, out, out_capacity);
}
