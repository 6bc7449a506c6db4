#include "rig_sim/static_thermal_run.h"

#include <unistd.h>

#include <filesystem>
#include <map>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sensor_sim/imu_unit.h"
#include "sensor_sim/param_reader.h"

namespace adahrs::rig_sim {
namespace {

std::vector<std::vector<std::string>> ReadCsv(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

TEST(StaticThermalRun, WritesARecordingWhoseTemperatureCountsFollowTheChamber) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("adahrs_static_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  StaticThermalRunConfig config;
  config.imu_units = 2;
  config.ads_units = 1;
  config.log_every = 100;  // one row per unit per second
  config.steps = {{45.0, 5.0, 600.0}, {25.0, 5.0, 60.0}};
  const StaticThermalRunSummary summary = RunStaticThermal(config, dir);

  const auto imu = ReadCsv(dir / "imu.csv");
  const auto ads = ReadCsv(dir / "ads.csv");
  ASSERT_GT(imu.size(), 100u);
  EXPECT_EQ(imu.size() - 1, summary.imu_rows);
  EXPECT_EQ(ads.size() - 1, summary.ads_rows);
  EXPECT_EQ(summary.imu_rows, 2 * summary.ads_rows);
  for (const auto& row : imu) EXPECT_EQ(row.size(), 26u);
  // The chamber must have reached 45 °C ± band during step 0; the gyro TEMP counts of each unit
  // rise from the start to the end of step 0 (8.4 mV/K: ~110 counts/°C, and the die lags).
  double max_chamber_c = -100;
  std::map<std::string, std::pair<double, double>> first_last_tx;
  for (size_t i = 1; i < imu.size(); ++i) {
    if (imu[i][3] != "0") continue;
    max_chamber_c = std::max(max_chamber_c, std::stod(imu[i][6]));
    auto& fl = first_last_tx[imu[i][1]];
    if (fl.first == 0) fl.first = std::stod(imu[i][23]);
    fl.second = std::stod(imu[i][23]);
    EXPECT_EQ(imu[i][4], "1");   // tag of step 0
    EXPECT_EQ(imu[i][5], "31");  // orientation
  }
  EXPECT_NEAR(max_chamber_c, 45.0, 0.3 + 1e-6);
  ASSERT_EQ(first_last_tx.size(), 2u);
  for (const auto& [unit, fl] : first_last_tx) EXPECT_GT(fl.second - fl.first, 110.0 * 10) << unit;

  // Truth files load back through the strict reader.
  const auto truth = sensor_sim::ParamReader::LoadFile((dir / "truth" / "IMU-0001.json").string());
  const sensor_sim::ParamReader reader(truth, "IMU-0001.json");
  EXPECT_EQ(sensor_sim::ImuUnitParams::FromJson(reader.Child("params")).serial, "IMU-0001");
  const auto meta = sensor_sim::ParamReader::LoadFile((dir / "meta.json").string());
  EXPECT_EQ(meta["units"].size(), 3u);
  EXPECT_EQ(meta["log_every"], 100);
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
