// IMU strategy files (docs/calibration-strategies.md "Strategy file"): what each key sets, and
// refusals that name the file and the JSON path.
#include "calib/imu_calibration/imu_strategy.h"

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/param_reader.h"

namespace adahrs::calib {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

std::filesystem::path Write(const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / "adahrs_imu_strategy_file_test.json";
  std::ofstream(path) << text;
  return path;
}

std::string LoadError(const std::string& text) {
  try {
    ImuStrategy::Load(Write(text));
  } catch (const common::ParamError& e) {
    return e.what();
  }
  return "no error";
}

constexpr const char* kHead = R"({"format": "adahrs-imu-strategy", "format_version": 1, )";

TEST(ImuStrategyFile, ReadsEveryKey) {
  const ImuStrategy s = ImuStrategy::Load(Write(std::string(kHead) +
                                                R"("strategy": "joint", "thermal_order": 2,
      "thermal_band_width_cnt": 220, "gyro_bias_wander": "estimated"})"));
  EXPECT_EQ(s.name, "joint");
  EXPECT_EQ(s.thermal_order, 2);
  EXPECT_EQ(s.band_width_cnt, 220.0);
  EXPECT_TRUE(s.estimate_gyro_wander);
  const ImuStrategy d = ImuStrategy::Load(Write(std::string(kHead) + R"("strategy": "joint"})"));
  EXPECT_FALSE(d.estimate_gyro_wander);
  EXPECT_FALSE(d.thermal_order.has_value());
}

TEST(ImuStrategyFile, RefusesNamingTheFileAndPath) {
  EXPECT_THAT(
      LoadError(std::string(kHead) + R"("strategy": "joint", "gyro_bias_wander": "allan"})"),
      AllOf(HasSubstr("adahrs_imu_strategy_file_test.json"),
            HasSubstr("$.gyro_bias_wander"),
            HasSubstr("\"allan\"")));
  EXPECT_THAT(LoadError(std::string(kHead) +
                        R"("strategy": "reference", "gyro_bias_wander": "datasheet"})"),
              AllOf(HasSubstr("$.gyro_bias_wander"), HasSubstr("only the joint strategy")));
  EXPECT_THAT(LoadError(std::string(kHead) + R"("strategy": "joint", "gyro_wander": "datasheet"})"),
              HasSubstr("$.gyro_wander"));
}

}  // namespace
}  // namespace adahrs::calib
