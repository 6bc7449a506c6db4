// A simulated unit's truth file (proving/evaluation/truth_file.h) in the schema the rig writes
// ({serial, kind, seed, model_profile, params}): read back to the same parameters; refused by
// name when it is another kind, another unit, or not a truth file.
#include "proving/evaluation/truth_file.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/param_reader.h"

namespace adahrs::proving {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const common::ParamError& e) {
    return e.what();
  }
  return "";
}

TEST(TruthFile, ReadsTheRigsSchemaAndRefusesAnotherUnitOrKind) {
  const fs::path dir =
      fs::temp_directory_path() / ("adahrs_truth_file_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto imu =
      sensor_sim::ImuUnitParams::Draw("IMU-0003", 33, sensor_sim::ModelProfile::kTruth);
  std::ofstream(dir / "IMU-0003.json") << nlohmann::json{
      {"serial", "IMU-0003"},
      {"kind", "imu"},
      {"seed", 33},
      {"model_profile", "truth"},
      {"params", imu.ToJson()}}.dump(2);
  const TruthFile t = ReadTruthFile(dir / "IMU-0003.json");
  EXPECT_EQ(t.kind, "imu");
  EXPECT_EQ(ImuTruth(t, "IMU-0003").ToJson(), imu.ToJson());
  EXPECT_THAT(
      ErrorOf([&] { ImuTruth(t, "IMU-0004"); }),
      HasSubstr("IMU-0003.json: $.params.serial: 'IMU-0003' is not the unit judged, 'IMU-0004'"));
  EXPECT_THAT(ErrorOf([&] { AdsTruth(t); }),
              HasSubstr("IMU-0003.json: $.kind: 'imu', not an ads truth file"));
  std::ofstream(dir / "bare.json") << imu.ToJson().dump();  // a params object alone
  EXPECT_THAT(ErrorOf([&] { ReadTruthFile(dir / "bare.json"); }),
              HasSubstr("bare.json: $.params: missing"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace adahrs::proving
