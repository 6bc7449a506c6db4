#include "rig_sim/static_thermal_run.h"

#include <unistd.h>

#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "common/param_reader.h"
#include "hil/recording/recording_reader.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::rig_sim {
namespace {

TEST(StaticThermalRun, WritesARecordingWhoseTemperatureCountsFollowTheChamber) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("adahrs_static_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  StaticThermalRunConfig config;
  config.imu_units = 2;
  config.ads_units = 1;
  config.log_every = 100;  // one row per unit per second
  config.steps = {{45.0, 5.0, 600.0}, {25.0, 5.0, 60.0}};
  const StaticThermalRunSummary summary = RunStaticThermal(config, dir);

  const hil::Recording rec = hil::ReadRecording(dir);  // the strict reader checks every cell
  const auto& imu = rec.imu;
  ASSERT_GT(imu.size(), 100u);
  EXPECT_EQ(imu.size(), summary.imu_rows);
  EXPECT_EQ(rec.ads.size(), summary.ads_rows);
  EXPECT_EQ(summary.imu_rows, 2 * summary.ads_rows);
  // The chamber must have reached 45 °C ± band during step 0; the gyro TEMP counts of each unit
  // rise from the start to the end of step 0 (8.4 mV/K: ~110 counts/°C, and the die lags).
  double max_chamber_c = -100;
  std::map<std::string, std::pair<double, double>> first_last_tx;
  for (const hil::ImuRecordRow& row : imu) {
    if (row.step != 0) continue;
    max_chamber_c = std::max(max_chamber_c, row.chamber_c);
    auto& fl = first_last_tx[row.unit];
    if (fl.first == 0) fl.first = row.temp_cnt[0];
    fl.second = row.temp_cnt[0];
    EXPECT_EQ(row.tag, 1);  // tag of step 0
    EXPECT_EQ(row.orientation, 31);
    EXPECT_EQ(row.mode, 0);  // raw: no compensated values
    EXPECT_FALSE(row.comp.has_value());
  }
  EXPECT_NEAR(max_chamber_c, 45.0, 0.3 + 1e-6);
  ASSERT_EQ(first_last_tx.size(), 2u);
  for (const auto& [unit, fl] : first_last_tx) EXPECT_GT(fl.second - fl.first, 110.0 * 10) << unit;

  // Truth files load back through the strict reader.
  const auto truth = common::ParamReader::LoadFile((dir / "truth" / "IMU-0001.json").string());
  const common::ParamReader reader(truth, "IMU-0001.json");
  EXPECT_EQ(sensor_sim::ImuUnitParams::FromJson(reader.Child("params")).serial, "IMU-0001");
  const hil::RecordingMeta meta = hil::ReadRecordingMeta(dir).meta;
  EXPECT_EQ(meta.units.size(), 3u);
  EXPECT_EQ(meta.extra.at("log_every"), 100);
  std::filesystem::remove_all(dir);
}

TEST(StaticThermalRun, RefusesAnEmptyProfileAndBadBatch) {
  StaticThermalRunConfig config;
  EXPECT_THROW(RunStaticThermal(config, "/tmp/never"), std::invalid_argument);
  config = StaticThermalRunConfig::Demo();
  config.imu_units = 5;
  EXPECT_THROW(RunStaticThermal(config, "/tmp/never"), std::invalid_argument);
}

}  // namespace
}  // namespace adahrs::rig_sim
