#include "rig_sim/rig_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/gravity.h"
#include "sensor_sim/ads_unit.h"

namespace adahrs::rig_sim {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

std::string ErrorOf(const nlohmann::json& json) {
  try {
    RigConfig::FromJson(json, "test.json");
  } catch (const common::ParamError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RigConfig, DefaultIsCompleteAndValid) {
  const RigConfig config = RigConfig::FromJson(DefaultRigConfig(), "default");
  EXPECT_EQ(config.imus.size(), 4u);
  EXPECT_EQ(config.ads.size(), 1u);
  EXPECT_EQ(config.imus[2].serial_number, 3u);
  EXPECT_EQ(config.imus[0].baud, 115200);
  EXPECT_EQ(config.model_profile, sensor_sim::ModelProfile::kTruth);
  EXPECT_EQ(config.truth_variant, sensor_sim::TruthVariant::kStandard);
  EXPECT_TRUE(config.faults.empty());
  EXPECT_EQ(ImuSerial(3), "IMU-0003");
  EXPECT_EQ(AdsSerial(12), "ADS-0012");
  // Local gravity is the station's WGS-84 normal gravity: 9.80620 m/s² at 45°, sea level
  // (NIMA TR8350.2 Somigliana; the free-air term is zero at h = 0).
  EXPECT_NEAR(config.LocalGravityMps2(), 9.806198, 1e-6);
}

TEST(RigConfig, ReadsUnitsStationAndFaults) {
  nlohmann::json j = DefaultRigConfig();
  j["station"]["latitude_deg"] = 0.0;
  j["station"]["height_m"] = 1000.0;
  j["units"]["model_profile"] = "nominal";
  j["units"]["truth_variant"] = "play_hysteresis";
  j["units"]["imu"] = {{{"serial_number", 12}, {"seed", 5}, {"orientation", 11}, {"baud", 57600}}};
  j["units"]["ads"] = nlohmann::json::array();
  j["faults"] = {{{"role", "imu1"}, {"fault", "drop_rate"}, {"rate", 0.01}},
                 {{"role", "imu1"}, {"fault", "unplugged"}, {"on", true}}};
  const RigConfig c = RigConfig::FromJson(j, "test.json");
  ASSERT_EQ(c.imus.size(), 1u);
  EXPECT_EQ(c.imus[0].orientation, 11);
  EXPECT_EQ(c.imus[0].baud, 57600);
  EXPECT_TRUE(c.ads.empty());
  EXPECT_EQ(c.model_profile, sensor_sim::ModelProfile::kNominal);
  EXPECT_EQ(c.truth_variant, sensor_sim::TruthVariant::kPlayHysteresis);
  ASSERT_EQ(c.faults.size(), 2u);
  EXPECT_TRUE(c.faults[0].is_rate);
  EXPECT_DOUBLE_EQ(c.faults[0].rate, 0.01);
  EXPECT_TRUE(c.faults[1].on);
  EXPECT_EQ(c.faults[1].where, "$.faults[1]");
  EXPECT_DOUBLE_EQ(c.LocalGravityMps2(), common::NormalGravityMps2(0.0, 1000.0));
}

// A slot naming a unit file (a truth file, or the model.json of `adahrs diagnose --model`) takes
// its params; a file of the other kind or serial is refused naming the slot and the file.
TEST(RigConfig, ASlotTakesItsUnitFromAModelFile) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "adahrs_rig_config_model";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  sensor_sim::AdsUnitParams ads =
      sensor_sim::AdsUnitParams::Draw("ADS-0001", 77, sensor_sim::ModelProfile::kNominal);
  ads.static_bridge.effects.pressure_hysteresis = true;
  ads.static_bridge.pressure_hysteresis_pct_fso = 0.0615;
  std::ofstream(dir / "model.json") << nlohmann::json{
      {"kind", "ads"},
      {"model_profile", "nominal"},
      {"params", ads.ToJson()}}.dump();
  nlohmann::json j = DefaultRigConfig();
  j["units"]["ads"][0]["model"] = "model.json";
  const RigConfig c = RigConfig::FromJson(j, (dir / "rig.json").string());
  ASSERT_FALSE(c.ads[0].model_params.is_null());
  const sensor_sim::AdsUnitParams read = sensor_sim::AdsUnitParams::FromJson(
      common::ParamReader(c.ads[0].model_params, c.ads[0].model_file, "$.params"));
  EXPECT_TRUE(read.static_bridge.effects.pressure_hysteresis);
  EXPECT_DOUBLE_EQ(read.static_bridge.pressure_hysteresis_pct_fso, 0.0615);
  EXPECT_TRUE(c.imus[0].model_params.is_null());

  j["units"]["ads"][0]["serial_number"] = 2;
  try {
    RigConfig::FromJson(j, (dir / "rig.json").string());
    ADD_FAILURE() << "accepted";
  } catch (const common::ParamError& e) {
    EXPECT_THAT(e.what(), HasSubstr("$.units.ads[0].model"));
    EXPECT_THAT(e.what(), HasSubstr("$.params.serial 'ADS-0001' is not this slot's ADS-0002"));
  }
  j["units"]["ads"][0]["serial_number"] = 1;
  j["units"]["imu"][0]["model"] = (dir / "model.json").string();
  try {
    RigConfig::FromJson(j, "rig.json");
    ADD_FAILURE() << "accepted";
  } catch (const common::ParamError& e) {
    EXPECT_THAT(e.what(), HasSubstr("$.units.imu[0].model"));
    EXPECT_THAT(e.what(), HasSubstr("kind 'ads' in an imu slot"));
  }
  std::filesystem::remove_all(dir);
}

TEST(RigConfig, ErrorsNameTheFileAndTheJsonPath) {
  nlohmann::json j = DefaultRigConfig();
  j["station"]["latitude"] = 45.0;
  EXPECT_THAT(ErrorOf(j), HasSubstr("test.json: $.station.latitude: unknown key"));

  j = DefaultRigConfig();
  j["units"]["imu"][2]["baud"] = 100;
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.units.imu[2].baud"));

  j = DefaultRigConfig();
  j["units"]["imu"][1]["orientation"] = 13;
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.units.imu[1].orientation: 13 is not a fixture code"));

  j = DefaultRigConfig();
  j["units"]["imu"][3]["serial_number"] = 1;
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.units.imu[3].serial_number: serial used twice"));

  j = DefaultRigConfig();
  j["units"]["imu"].push_back(j["units"]["imu"][0]);
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.units.imu: expected an array of 0…4 objects"));

  j = DefaultRigConfig();
  j["units"]["model_profile"] = "perfect";
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.units.model_profile"));

  j = DefaultRigConfig();
  j["units"]["truth_variant"] = "ideal";
  EXPECT_THAT(ErrorOf(j), AllOf(HasSubstr("$.units.truth_variant"), HasSubstr("play_hysteresis")));

  j = DefaultRigConfig();
  j["instruments"]["tea_urn"] = nlohmann::json::object();
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.instruments.tea_urn: unknown instrument kind"));

  j = DefaultRigConfig();
  j["time_scale"] = 0.0;
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.time_scale"));

  j = DefaultRigConfig();
  j["faults"] = {{{"role", "imu1"}, {"fault", "drop_rate"}, {"rate", 2.0}}};
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.faults[0].rate"));

  j = DefaultRigConfig();
  j.erase("faults");
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.faults: missing key"));
}

}  // namespace
}  // namespace adahrs::rig_sim
