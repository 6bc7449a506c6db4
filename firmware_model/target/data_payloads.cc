#include "firmware_model/target/data_payloads.h"

#include "firmware_model/target/byte_order.h"
#include "firmware_model/target/packet_codec.h"

namespace adahrs::firmware_model {
namespace {

bool IsImuMode(uint8_t mode) {
  return mode <= static_cast<uint8_t>(ImuMode::kFullyCalibrated);
}

bool IsAdsMode(uint8_t mode) {
  return mode <= static_cast<uint8_t>(AdsMode::kSurface);
}

// Field offsets (docs/unit-protocol.md §4.2 and §5.2).
constexpr uint8_t kImuGyroOffset = 24;
constexpr uint8_t kImuTempOffset = 36;
constexpr uint8_t kImuModeOffset = 42;
constexpr uint8_t kImuCompensatedOffset = 43;
constexpr uint8_t kAdsModeOffset = 20;
constexpr uint8_t kAdsCompensatedOffset = 21;

}  // namespace

uint8_t ImuPayloadBytes(ImuMode mode) {
  return mode == ImuMode::kRaw ? kImuRawPayloadBytes : kImuCompensatedPayloadBytes;
}

uint8_t AdsPayloadBytes(AdsMode mode) {
  return mode == AdsMode::kRaw ? kAdsRawPayloadBytes : kAdsCompensatedPayloadBytes;
}

uint8_t EncodeImuPayload(const ImuDataPayload& data, uint8_t* out, uint8_t capacity) {
  if (!IsImuMode(static_cast<uint8_t>(data.mode))) {
    return 0;
  }
  const uint8_t length = ImuPayloadBytes(data.mode);
  if (capacity < length) {
    return 0;
  }
  for (uint8_t i = 0; i < kImuAccelChannels; ++i) {
    PutU16Le(out + 4 * i, data.accel[i].t1_cnt);
    PutU16Le(out + 4 * i + 2, data.accel[i].t2_cnt);
  }
  for (uint8_t i = 0; i < kImuGyroChannels; ++i) {
    PutI32Le(out + kImuGyroOffset + 4 * i, data.gyro_cnt[i]);
  }
  for (uint8_t i = 0; i < kImuTempChannels; ++i) {
    PutU16Le(out + kImuTempOffset + 2 * i, data.temp_cnt[i]);
  }
  out[kImuModeOffset] = static_cast<uint8_t>(data.mode);
  if (data.mode != ImuMode::kRaw) {
    for (uint8_t i = 0; i < kImuCompensatedValues; ++i) {
      PutI32Le(out + kImuCompensatedOffset + 4 * i, data.compensated_lsb[i]);
    }
  }
  return length;
}

uint8_t EncodeAdsPayload(const AdsDataPayload& data, uint8_t* out, uint8_t capacity) {
  if (!IsAdsMode(static_cast<uint8_t>(data.mode))) {
    return 0;
  }
  const uint8_t length = AdsPayloadBytes(data.mode);
  if (capacity < length) {
    return 0;
  }
  PutI32Le(out, data.ps_cnt);
  PutI32Le(out + 4, data.pt_cnt);
  PutI32Le(out + 8, data.ps_bridge_cnt);
  PutI32Le(out + 12, data.pt_bridge_cnt);
  PutI32Le(out + 16, data.oat_cnt);
  out[kAdsModeOffset] = static_cast<uint8_t>(data.mode);
  if (data.mode != AdsMode::kRaw) {
    for (uint8_t i = 0; i < kAdsCompensatedValues; ++i) {
      PutI32Le(out + kAdsCompensatedOffset + 4 * i, data.compensated_lsb[i]);
    }
  }
  return length;
}

bool DecodeImuPayload(const uint8_t* payload, uint8_t length, ImuDataPayload* data) {
  if (length < kImuRawPayloadBytes || !IsImuMode(payload[kImuModeOffset])) {
    return false;
  }
  const ImuMode mode = static_cast<ImuMode>(payload[kImuModeOffset]);
  if (length != ImuPayloadBytes(mode)) {
    return false;
  }
  for (uint8_t i = 0; i < kImuAccelChannels; ++i) {
    data->accel[i].t1_cnt = GetU16Le(payload + 4 * i);
    data->accel[i].t2_cnt = GetU16Le(payload + 4 * i + 2);
  }
  for (uint8_t i = 0; i < kImuGyroChannels; ++i) {
    data->gyro_cnt[i] = GetI32Le(payload + kImuGyroOffset + 4 * i);
  }
  for (uint8_t i = 0; i < kImuTempChannels; ++i) {
    data->temp_cnt[i] = GetU16Le(payload + kImuTempOffset + 2 * i);
  }
  data->mode = mode;
  for (uint8_t i = 0; i < kImuCompensatedValues; ++i) {
    data->compensated_lsb[i] =
        mode == ImuMode::kRaw ? 0 : GetI32Le(payload + kImuCompensatedOffset + 4 * i);
  }
  return true;
}

bool DecodeAdsPayload(const uint8_t* payload, uint8_t length, AdsDataPayload* data) {
  if (length < kAdsRawPayloadBytes || !IsAdsMode(payload[kAdsModeOffset])) {
    return false;
  }
  const AdsMode mode = static_cast<AdsMode>(payload[kAdsModeOffset]);
  if (length != AdsPayloadBytes(mode)) {
    return false;
  }
  data->ps_cnt = GetI32Le(payload);
  data->pt_cnt = GetI32Le(payload + 4);
  data->ps_bridge_cnt = GetI32Le(payload + 8);
  data->pt_bridge_cnt = GetI32Le(payload + 12);
  data->oat_cnt = GetI32Le(payload + 16);
  data->mode = mode;
  for (uint8_t i = 0; i < kAdsCompensatedValues; ++i) {
    data->compensated_lsb[i] =
        mode == AdsMode::kRaw ? 0 : GetI32Le(payload + kAdsCompensatedOffset + 4 * i);
  }
  return true;
}

uint16_t EncodeImuDataFrame(const ImuDataPayload& data, uint8_t sequence, uint8_t tag, uint8_t* out,
                            uint16_t out_capacity) {
  uint8_t payload[kImuCompensatedPayloadBytes];
  const uint8_t length = EncodeImuPayload(data, payload, kImuCompensatedPayloadBytes);
  if (length == 0) {
    return 0;
  }
  return EncodeFrame(static_cast<uint8_t>(PacketType::kImuData), sequence, tag, payload, length, out,
                     out_capacity);
}

uint16_t EncodeAdsDataFrame(const AdsDataPayload& data, uint8_t sequence, uint8_t tag, uint8_t* out,
                            uint16_t out_capacity) {
  uint8_t payload[kAdsCompensatedPayloadBytes];
  const uint8_t length = EncodeAdsPayload(data, payload, kAdsCompensatedPayloadBytes);
  if (length == 0) {
    return 0;
  }
  return EncodeFrame(static_cast<uint8_t>(PacketType::kAdsData), sequence, tag, payload, length, out,
                     out_capacity);
}

}  // namespace adahrs::firmware_model
