// The units' compensated rows against the model of the constants they hold: a recording written
// here with the model's own values (the firmware's law, reference_compensator.h) and one row
// moved by a known amount gives that amount and nothing else; flagged rows are counted apart,
// raw rows and units without constants are passed over.
#include "calib/imu_calibration/mode_conformance.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "firmware_model/reference_compensator.h"
#include "hil/recording/recording_writer.h"
#include "tests/firmware_model/realistic_constants.h"

namespace adahrs::calib {
namespace {

namespace fm = firmware_model;

TEST(ModeConformance, FindsTheOneRowThatLeavesTheModelAndCountsFlaggedRowsApart) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("adahrs_mode_conformance_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const fm::ImuCalibrationConstants c = fm::testing::RealisticImu(11);
  constexpr double kMovedG = 3e-6;
  {
    hil::RecordingWriter writer(dir);
    writer.WriteMetaJson(
        {{"run_id", "conformance"},
         {"status", "complete"},
         {"local_gravity_mps2", 9.80665},
         {"units",
          {{{"kind", "imu"}, {"serial", "IMU-0001"}}, {{"kind", "imu"}, {"serial", "IMU-0002"}}}}});
    for (int i = 1; i <= 300; ++i) {
      hil::ImuRecordRow row;
      row.unit = i % 3 == 0 ? "IMU-0002" : "IMU-0001";
      row.t_s = 0.01 * i;
      row.seq = static_cast<uint32_t>(i & 0xFF);
      row.orientation = 31;
      for (size_t ch = 0; ch < 6; ++ch) {
        row.accel_ticks[2 * ch] = static_cast<uint16_t>(4000 + 3 * i + 17 * ch);
        row.accel_ticks[2 * ch + 1] = 8000;
      }
      for (size_t g = 0; g < 3; ++g) {
        row.gyro_cnt[g] = 4194304 + 50 * i;
        row.temp_cnt[g] = static_cast<uint16_t>(30000 + 10 * i);
      }
      row.mode = i <= 30 ? 0 : 2;
      if (row.mode != 0) {
        fm::ImuRawFrame raw{};
        for (size_t ch = 0; ch < 6; ++ch) {
          raw.t1_cnt[ch] = row.accel_ticks[2 * ch];
          raw.t2_cnt[ch] = row.accel_ticks[2 * ch + 1];
        }
        for (size_t g = 0; g < 3; ++g) {
          raw.gyro_cnt[g] = row.gyro_cnt[g];
          raw.temp_cnt[g] = row.temp_cnt[g];
        }
        row.comp = fm::ImuReference(c, fm::ImuCompensationMode::kSensorCalibrated, raw);
        if (i == 100) (*row.comp)[4] += kMovedG;
        if (i == 200) {
          (*row.comp)[0] += 1.0;  // flagged: not compared
          row.comp_flags = 2;
        }
      }
      writer.Append(row);
    }
    writer.Flush(true);
  }
  const std::vector<ModeConformance> found = CheckModeConformance(dir, {{"IMU-0001", c}});
  ASSERT_EQ(found.size(), 1u);  // IMU-0002 has no constants here
  const ModeConformance& m = found[0];
  EXPECT_EQ(m.serial, "IMU-0001");
  EXPECT_EQ(m.mode, 2);
  EXPECT_EQ(m.flagged_rows, 1);
  EXPECT_EQ(m.rows, 200 - 20 - 1);  // IMU-0001's rows past the first 30, less the flagged one
  for (size_t i = 0; i < 9; ++i) {
    if (i == 4) {
      // The value is written in the shortest text that reads back to the same double.
      EXPECT_NEAR(m.channels[i].max_abs_diff, kMovedG, 1e-15);
      EXPECT_NEAR(m.channels[i].rms_diff, kMovedG / std::sqrt(double(m.rows)), 1e-15);
    } else {
      EXPECT_EQ(m.channels[i].max_abs_diff, 0.0) << i;
    }
  }
  EXPECT_EQ(m.ToJson()["channels"][4]["max_abs_diff"], m.channels[4].max_abs_diff);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace adahrs::calib
