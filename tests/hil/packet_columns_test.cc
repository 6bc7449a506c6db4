#include "hil/recording/packet_columns.h"

#include <cmath>

#include <gtest/gtest.h>

namespace adahrs::hil {
namespace {

namespace fm = firmware_model;

// Expected values come from the LSBs that compensated_frame.h documents per mode and slot
// (2^-31 duty, 2^-8 count, 2^-27 g, 2^-23 deg/s, 2^-23 m/s^2, 2^-15 ft, 2^-22 kt): a word w
// stands for w * LSB, exactly.
fm::ImuDataPayload ImuPayload(fm::ImuCompensationMode mode, int32_t word) {
  fm::ImuDataPayload p{};
  p.mode = mode;
  for (int i = 0; i < 9; ++i) p.compensated.value[i] = word;
  p.compensated.flags = fm::kFlagOutputSaturated;
  for (int ch = 0; ch < 6; ++ch) {
    p.raw.t1_cnt[ch] = static_cast<uint16_t>(100 + ch);
    p.raw.t2_cnt[ch] = static_cast<uint16_t>(200 + ch);
  }
  p.raw.gyro_cnt[2] = 4194304;
  p.raw.temp_cnt[1] = 33000;
  return p;
}

TEST(PacketColumns, RawModeLeavesCompensatedColumnsEmpty) {
  ImuRecordRow row;
  SetPacketColumns(ImuPayload(fm::ImuCompensationMode::kRaw, 0), row);
  EXPECT_EQ(row.mode, 0);
  EXPECT_FALSE(row.comp.has_value());
  EXPECT_EQ(row.accel_ticks[0], 100);
  EXPECT_EQ(row.accel_ticks[1], 200);
  EXPECT_EQ(row.accel_ticks[11], 205);
  EXPECT_EQ(row.gyro_cnt[2], 4194304);
  EXPECT_EQ(row.temp_cnt[1], 33000);
}

TEST(PacketColumns, ThermalModeIsDutyAndCounts) {
  ImuRecordRow row;
  SetPacketColumns(ImuPayload(fm::ImuCompensationMode::kThermal, 1 << 20), row);
  ASSERT_TRUE(row.comp.has_value());
  EXPECT_EQ(row.mode, 1);
  EXPECT_EQ((*row.comp)[0], std::ldexp(1.0, 20 - 31));  // duty LSB 2^-31
  EXPECT_EQ((*row.comp)[6], std::ldexp(1.0, 20 - 8));   // count LSB 2^-8
  EXPECT_EQ(row.comp_flags, fm::kFlagOutputSaturated);
}

TEST(PacketColumns, SensorCalibratedModeIsGAndDps) {
  ImuRecordRow row;
  SetPacketColumns(ImuPayload(fm::ImuCompensationMode::kSensorCalibrated, 1 << 27), row);
  EXPECT_EQ((*row.comp)[5], 1.0);   // 2^27 * 2^-27 g
  EXPECT_EQ((*row.comp)[8], 16.0);  // 2^27 * 2^-23 deg/s
}

TEST(PacketColumns, FullyCalibratedModeIsMps2DpsAndG) {
  ImuRecordRow row;
  SetPacketColumns(ImuPayload(fm::ImuCompensationMode::kFullyCalibrated, -(1 << 23)), row);
  EXPECT_EQ((*row.comp)[0], -1.0);         // m/s^2, LSB 2^-23
  EXPECT_EQ((*row.comp)[3], -1.0);         // deg/s, LSB 2^-23
  EXPECT_EQ((*row.comp)[6], -1.0 / 16.0);  // g, LSB 2^-27
}

TEST(PacketColumns, AdsSurfaceModeIsFeetAndKnots) {
  fm::AdsDataPayload p{};
  p.raw.ps_cnt = -8388608;
  p.raw.oat_cnt = 77;
  p.mode = fm::AdsCompensationMode::kSurface;
  p.compensated.value[0] = 35000 << 15;  // 35,000 ft at 2^-15 ft
  p.compensated.value[1] = 250 << 22;    // 250 kt at 2^-22 kt
  AdsRecordRow row;
  SetPacketColumns(p, row);
  EXPECT_EQ(row.ps_cnt, -8388608);
  EXPECT_EQ(row.oat_cnt, 77);
  EXPECT_EQ(row.mode, 1);
  EXPECT_EQ(row.alt_ft, 35000.0);
  EXPECT_EQ(row.cas_kt, 250.0);
  p.mode = fm::AdsCompensationMode::kRaw;
  SetPacketColumns(p, row);
  EXPECT_FALSE(row.alt_ft.has_value());
  EXPECT_FALSE(row.cas_kt.has_value());
}

}  // namespace
}  // namespace adahrs::hil
