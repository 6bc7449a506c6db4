// Data packet payloads (docs/unit-protocol.md §4-5): byte layout at the documented offsets,
// round trips in every mode with extreme values, and refusal of inconsistent payloads.
#include "firmware_model/unit_firmware.h"

#include <cstdint>
#include <limits>

#include <gtest/gtest.h>

namespace adahrs::firmware_model {
namespace {

ImuDataPayload ExtremeImuPayload(ImuCompensationMode mode) {
  ImuDataPayload data{};
  for (int i = 0; i < 6; ++i) {
    data.raw.t1_cnt[i] = static_cast<uint16_t>(0x1000 * i + 1);
    data.raw.t2_cnt[i] = static_cast<uint16_t>(0xFFFF - i);
  }
  data.raw.gyro_cnt[0] = std::numeric_limits<int32_t>::min();
  data.raw.gyro_cnt[1] = std::numeric_limits<int32_t>::max();
  data.raw.gyro_cnt[2] = -1;
  data.raw.temp_cnt[0] = 0;
  data.raw.temp_cnt[1] = 0xFFFF;
  data.raw.temp_cnt[2] = 0x8000;
  data.mode = mode;
  for (int i = 0; i < 9; ++i) {
    data.compensated.value[i] = (i % 2 == 0 ? -1 : 1) * (0x01020304 * i + 7);
  }
  data.compensated.flags = 0x8005;
  return data;
}

void ExpectImuEqual(const ImuDataPayload& a, const ImuDataPayload& b, bool with_compensated) {
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(a.raw.t1_cnt[i], b.raw.t1_cnt[i]);
    EXPECT_EQ(a.raw.t2_cnt[i], b.raw.t2_cnt[i]);
  }
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(a.raw.gyro_cnt[i], b.raw.gyro_cnt[i]);
    EXPECT_EQ(a.raw.temp_cnt[i], b.raw.temp_cnt[i]);
  }
  EXPECT_EQ(a.mode, b.mode);
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(with_compensated ? a.compensated.value[i] : 0, b.compensated.value[i]);
  }
  EXPECT_EQ(with_compensated ? a.compensated.flags : 0, b.compensated.flags);
}

TEST(DataPayloadsTest, ImuLayoutIsLittleEndianAtDocumentedOffsets) {
  ImuDataPayload data = ExtremeImuPayload(ImuCompensationMode::kFullyCalibrated);
  data.raw.t1_cnt[1] = 0xBEEF;        // ax1 T1 at offset 4
  data.raw.t2_cnt[5] = 0x1234;        // ay2 T2 at offset 22
  data.raw.gyro_cnt[0] = 0x01020304;  // gx at offset 24
  data.raw.temp_cnt[2] = 0xCAFE;      // tz at offset 40
  data.compensated.value[8] = -2;     // value 8 at offset 43 + 32
  data.compensated.flags = 0x0102;    // flags at offset 79
  uint8_t out[kImuCompensatedPayloadBytes];
  ASSERT_EQ(EncodeImuPayload(data, out, sizeof(out)), 81);
  EXPECT_EQ(out[4], 0xEF);
  EXPECT_EQ(out[5], 0xBE);
  EXPECT_EQ(out[22], 0x34);
  EXPECT_EQ(out[23], 0x12);
  EXPECT_EQ(out[24], 0x04);
  EXPECT_EQ(out[27], 0x01);
  EXPECT_EQ(out[40], 0xFE);
  EXPECT_EQ(out[41], 0xCA);
  EXPECT_EQ(out[42], 0x03);  // mode byte
  EXPECT_EQ(out[75], 0xFE);
  EXPECT_EQ(out[78], 0xFF);
  EXPECT_EQ(out[79], 0x02);
  EXPECT_EQ(out[80], 0x01);
}

TEST(DataPayloadsTest, ImuRoundTripInEveryMode) {
  for (const auto mode : {ImuCompensationMode::kRaw,
                          ImuCompensationMode::kThermal,
                          ImuCompensationMode::kSensorCalibrated,
                          ImuCompensationMode::kFullyCalibrated}) {
    const ImuDataPayload data = ExtremeImuPayload(mode);
    uint8_t out[kImuCompensatedPayloadBytes];
    const uint8_t length = EncodeImuPayload(data, out, sizeof(out));
    EXPECT_EQ(length, mode == ImuCompensationMode::kRaw ? 43 : 81);
    ImuDataPayload decoded{};
    ASSERT_TRUE(DecodeImuPayload(out, length, &decoded));
    ExpectImuEqual(data, decoded, mode != ImuCompensationMode::kRaw);
  }
}

TEST(DataPayloadsTest, AdsLayoutAndRoundTrip) {
  AdsDataPayload data{};
  data.raw.ps_cnt = -8388608;  // most negative 24-bit code, sign-extended
  data.raw.pt_cnt = 8388607;
  data.raw.ps_bridge_cnt = 0x00123456;
  data.raw.pt_bridge_cnt = -1;
  data.raw.oat_cnt = 42;
  data.mode = AdsCompensationMode::kSurface;
  data.compensated.value[0] = 0x0A0B0C0D;
  data.compensated.value[1] = -7;
  data.compensated.flags = 0x0002;
  uint8_t out[kAdsCompensatedPayloadBytes];
  ASSERT_EQ(EncodeAdsPayload(data, out, sizeof(out)), 31);
  EXPECT_EQ(out[0], 0x00);
  EXPECT_EQ(out[2], 0x80);
  EXPECT_EQ(out[3], 0xFF);  // sign extension of the 24-bit code
  EXPECT_EQ(out[8], 0x56);
  EXPECT_EQ(out[20], 0x01);
  EXPECT_EQ(out[21], 0x0D);
  EXPECT_EQ(out[29], 0x02);
  AdsDataPayload decoded{};
  ASSERT_TRUE(DecodeAdsPayload(out, 31, &decoded));
  EXPECT_EQ(decoded.raw.ps_cnt, data.raw.ps_cnt);
  EXPECT_EQ(decoded.raw.pt_cnt, data.raw.pt_cnt);
  EXPECT_EQ(decoded.raw.ps_bridge_cnt, data.raw.ps_bridge_cnt);
  EXPECT_EQ(decoded.raw.pt_bridge_cnt, data.raw.pt_bridge_cnt);
  EXPECT_EQ(decoded.raw.oat_cnt, data.raw.oat_cnt);
  EXPECT_EQ(decoded.compensated.value[0], data.compensated.value[0]);
  EXPECT_EQ(decoded.compensated.value[1], data.compensated.value[1]);
  EXPECT_EQ(decoded.compensated.flags, data.compensated.flags);

  data.mode = AdsCompensationMode::kRaw;
  ASSERT_EQ(EncodeAdsPayload(data, out, sizeof(out)), 21);
  ASSERT_TRUE(DecodeAdsPayload(out, 21, &decoded));
  EXPECT_EQ(decoded.mode, AdsCompensationMode::kRaw);
  EXPECT_EQ(decoded.compensated.value[0], 0);
  EXPECT_EQ(decoded.compensated.flags, 0);
}

TEST(DataPayloadsTest, RefusesInconsistentPayloads) {
  uint8_t out[kImuCompensatedPayloadBytes];
  const ImuDataPayload raw = ExtremeImuPayload(ImuCompensationMode::kRaw);
  ASSERT_EQ(EncodeImuPayload(raw, out, sizeof(out)), 43);
  ImuDataPayload decoded = ExtremeImuPayload(ImuCompensationMode::kThermal);
  const ImuDataPayload before = decoded;
  // Raw mode byte with the compensated length, and a compensated mode with the raw length.
  EXPECT_FALSE(DecodeImuPayload(out, 81, &decoded));
  out[42] = 0x02;
  EXPECT_FALSE(DecodeImuPayload(out, 43, &decoded));
  // Mode byte 4 is undefined for an IMU.
  out[42] = 0x04;
  EXPECT_FALSE(DecodeImuPayload(out, 43, &decoded));
  EXPECT_FALSE(DecodeImuPayload(out, 42, &decoded));
  ExpectImuEqual(before, decoded, true);
  // Too small a buffer and an undefined mode are refused by the encoder.
  EXPECT_EQ(EncodeImuPayload(raw, out, 42), 0);
  ImuDataPayload bad_mode = raw;
  bad_mode.mode = static_cast<ImuCompensationMode>(7);
  EXPECT_EQ(EncodeImuPayload(bad_mode, out, sizeof(out)), 0);
  AdsDataPayload ads{};
  ads.mode = static_cast<AdsCompensationMode>(2);
  EXPECT_EQ(EncodeAdsPayload(ads, out, sizeof(out)), 0);
}

}  // namespace
}  // namespace adahrs::firmware_model
