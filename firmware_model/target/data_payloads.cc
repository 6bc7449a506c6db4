#include "firmware_model/target/data_payloads.h"
#include "firmware_model/target/imu_constants.h"

#include "firmware_model/target/byte_order.h"
#include "firmware_model/target/packet_codec.h"

namespace adahrs::firmware_model {
namespace {

// Field offsets (docs/unit-protocol.md §4.2 and §5.2).
constexpr uint8_t kImuGyroOffset = 24;
constexpr uint8_t kImuTempOffset = 36;
constexpr uint8_t kImuModeOffset = 42;
constexpr uint8_t kImuValuesOffset = 43;
constexpr uint8_t kImuFlagsOffset = 79;
constexpr uint8_t kAdsModeOffset = 20;
constexpr uint8_t kAdsValuesOffset = 21;
constexpr uint8_t kAdsFlagsOffset = 29;

// The compensated values and their flags word, at their offsets in a payload.
void PutCompensated(const int32_t* value,
                    uint8_t count,
                    uint16_t flags,
                    uint8_t values_offset,
                    uint8_t flags_offset,
                    uint8_t* out) {
  for (uint8_t i = 0; i < count; ++i) {
    PutI32Le(out + values_offset + 4 * i, value[i]);
  }
  PutU16Le(out + flags_offset, flags);
}

// Reads them back; a raw payload (`has_values` false) carries none and reads as zeros.
void GetCompensated(const uint8_t* payload,
                    bool has_values,
                    uint8_t values_offset,
                    uint8_t flags_offset,
                    int32_t* value,
                    uint8_t count,
                    uint16_t* flags) {
  for (uint8_t i = 0; i < count; ++i) {
    value[i] = has_values ? GetI32Le(payload + values_offset + 4 * i) : 0;
  }
  *flags = has_values ? GetU16Le(payload + flags_offset) : uint16_t{0};
}

// Frames a payload an encoder wrote (`length` 0: the encoder refused it, and so does this).
uint16_t FrameDataPayload(PacketType type,
                          const uint8_t* payload,
                          uint8_t length,
                          uint8_t sequence,
                          uint8_t tag,
                          uint8_t* out,
                          uint16_t out_capacity) {
  if (length == 0) {
    return 0;
  }
  return EncodeFrame(static_cast<uint8_t>(type), sequence, tag, payload, length, out, out_capacity);
}

}  // namespace

bool IsImuModeByte(uint8_t mode) {
  return mode <= static_cast<uint8_t>(ImuCompensationMode::kFullyCalibrated);
}

bool IsAdsModeByte(uint8_t mode) {
  return mode <= static_cast<uint8_t>(AdsCompensationMode::kSurface);
}

uint8_t ImuPayloadBytes(ImuCompensationMode mode) {
  return mode == ImuCompensationMode::kRaw ? kImuRawPayloadBytes : kImuCompensatedPayloadBytes;
}

uint8_t AdsPayloadBytes(AdsCompensationMode mode) {
  return mode == AdsCompensationMode::kRaw ? kAdsRawPayloadBytes : kAdsCompensatedPayloadBytes;
}

uint8_t EncodeImuPayload(const ImuDataPayload& data, uint8_t* out, uint8_t capacity) {
  if (!IsImuModeByte(static_cast<uint8_t>(data.mode))) {
    return 0;
  }
  const uint8_t length = ImuPayloadBytes(data.mode);
  if (capacity < length) {
    return 0;
  }
  for (uint8_t i = 0; i < kAccelChannels; ++i) {
    PutU16Le(out + 4 * i, data.raw.t1_cnt[i]);
    PutU16Le(out + 4 * i + 2, data.raw.t2_cnt[i]);
  }
  for (uint8_t i = 0; i < kGyroChannels; ++i) {
    PutI32Le(out + kImuGyroOffset + 4 * i, data.raw.gyro_cnt[i]);
  }
  for (uint8_t i = 0; i < kTempSensors; ++i) {
    PutU16Le(out + kImuTempOffset + 2 * i, data.raw.temp_cnt[i]);
  }
  out[kImuModeOffset] = static_cast<uint8_t>(data.mode);
  if (data.mode != ImuCompensationMode::kRaw) {
    PutCompensated(data.compensated.value,
                   kImuOutputValues,
                   data.compensated.flags,
                   kImuValuesOffset,
                   kImuFlagsOffset,
                   out);
  }
  return length;
}

uint8_t EncodeAdsPayload(const AdsDataPayload& data, uint8_t* out, uint8_t capacity) {
  if (!IsAdsModeByte(static_cast<uint8_t>(data.mode))) {
    return 0;
  }
  const uint8_t length = AdsPayloadBytes(data.mode);
  if (capacity < length) {
    return 0;
  }
  PutI32Le(out, data.raw.ps_cnt);
  PutI32Le(out + 4, data.raw.pt_cnt);
  PutI32Le(out + 8, data.raw.ps_bridge_cnt);
  PutI32Le(out + 12, data.raw.pt_bridge_cnt);
  PutI32Le(out + 16, data.raw.oat_cnt);
  out[kAdsModeOffset] = static_cast<uint8_t>(data.mode);
  if (data.mode != AdsCompensationMode::kRaw) {
    PutCompensated(data.compensated.value,
                   kAdsOutputValues,
                   data.compensated.flags,
                   kAdsValuesOffset,
                   kAdsFlagsOffset,
                   out);
  }
  return length;
}

bool DecodeImuPayload(const uint8_t* payload, uint8_t length, ImuDataPayload* data) {
  if (length < kImuRawPayloadBytes || !IsImuModeByte(payload[kImuModeOffset])) {
    return false;
  }
  const auto mode = static_cast<ImuCompensationMode>(payload[kImuModeOffset]);
  if (length != ImuPayloadBytes(mode)) {
    return false;
  }
  for (uint8_t i = 0; i < kAccelChannels; ++i) {
    data->raw.t1_cnt[i] = GetU16Le(payload + 4 * i);
    data->raw.t2_cnt[i] = GetU16Le(payload + 4 * i + 2);
  }
  for (uint8_t i = 0; i < kGyroChannels; ++i) {
    data->raw.gyro_cnt[i] = GetI32Le(payload + kImuGyroOffset + 4 * i);
  }
  for (uint8_t i = 0; i < kTempSensors; ++i) {
    data->raw.temp_cnt[i] = GetU16Le(payload + kImuTempOffset + 2 * i);
  }
  data->mode = mode;
  GetCompensated(payload,
                 mode != ImuCompensationMode::kRaw,
                 kImuValuesOffset,
                 kImuFlagsOffset,
                 data->compensated.value,
                 kImuOutputValues,
                 &data->compensated.flags);
  return true;
}

bool DecodeAdsPayload(const uint8_t* payload, uint8_t length, AdsDataPayload* data) {
  if (length < kAdsRawPayloadBytes || !IsAdsModeByte(payload[kAdsModeOffset])) {
    return false;
  }
  const auto mode = static_cast<AdsCompensationMode>(payload[kAdsModeOffset]);
  if (length != AdsPayloadBytes(mode)) {
    return false;
  }
  data->raw.ps_cnt = GetI32Le(payload);
  data->raw.pt_cnt = GetI32Le(payload + 4);
  data->raw.ps_bridge_cnt = GetI32Le(payload + 8);
  data->raw.pt_bridge_cnt = GetI32Le(payload + 12);
  data->raw.oat_cnt = GetI32Le(payload + 16);
  data->mode = mode;
  GetCompensated(payload,
                 mode != AdsCompensationMode::kRaw,
                 kAdsValuesOffset,
                 kAdsFlagsOffset,
                 data->compensated.value,
                 kAdsOutputValues,
                 &data->compensated.flags);
  return true;
}

uint16_t EncodeImuDataFrame(const ImuDataPayload& data,
                            uint8_t sequence,
                            uint8_t tag,
                            uint8_t* out,
                            uint16_t out_capacity) {
  uint8_t payload[kImuCompensatedPayloadBytes];
  const uint8_t length = EncodeImuPayload(data, payload, kImuCompensatedPayloadBytes);
  return FrameDataPayload(PacketType::kImuData, payload, length, sequence, tag, out, out_capacity);
}

uint16_t EncodeAdsDataFrame(const AdsDataPayload& data,
                            uint8_t sequence,
                            uint8_t tag,
                            uint8_t* out,
                            uint16_t out_capacity) {
  uint8_t payload[kAdsCompensatedPayloadBytes];
  const uint8_t length = EncodeAdsPayload(data, payload, kAdsCompensatedPayloadBytes);
  return FrameDataPayload(PacketType::kAdsData, payload, length, sequence, tag, out, out_capacity);
}

}  // namespace adahrs::firmware_model
