#include "hil/station.h"
#include "adahrs_build_paths.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace adahrs::hil {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

const std::string kExample =
    std::string(ADAHRS_SOURCE_DIR) + "/docs/examples/station-virtual-rig.json";

nlohmann::json Example() { return common::ParamReader::LoadFile(kExample); }

std::string ErrorOf(const nlohmann::json& j) {
  try {
    Station::FromJson(common::ParamReader(j, "station.json"));
  } catch (const common::ParamError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(Station, TheDocumentedExampleLoads) {
  const Station st = Station::Load(kExample);
  EXPECT_EQ(st.time_scale, 100.0);
  ASSERT_NE(st.Instrument("imu_chamber"), nullptr);
  EXPECT_EQ(st.Instrument("imu_chamber")->type, InstrumentType::kWatlowF4);
  EXPECT_EQ(st.Instrument("imu_chamber")->address, 1);
  EXPECT_EQ(st.Instrument("adts"), nullptr);
  ASSERT_EQ(st.units.size(), 2u);
  EXPECT_EQ(st.units[1].port.baud, 115200u);
  // WGS-84 normal gravity at 34.7° N, 190 m, by hand: Somigliana
  // 9.7803253359·(1 + 0.00193185265·sin²φ)/√(1 − 0.00669438·sin²φ) = 9.797079 with sin²φ =
  // 0.324082, free air −3.086e-6·190 = −0.000586: 9.796493 m/s².
  EXPECT_NEAR(st.local_gravity_mps2, 9.796493, 1e-5);
}

TEST(Station, OperatorIsTheVirtualFixtureOrTheConsole) {
  const Station st = Station::Load(kExample);
  EXPECT_EQ(st.op.type, OperatorType::kVirtualFixture);
  EXPECT_EQ(st.op.port.path, "runs/rig/ports/control");

  nlohmann::json j = Example();
  j.erase("operator");
  EXPECT_EQ(Station::FromJson(common::ParamReader(j, "station.json")).op.type,
            OperatorType::kConsole);
  j["operator"] = {{"type", "console"}};
  EXPECT_EQ(Station::FromJson(common::ParamReader(j, "station.json")).op.type,
            OperatorType::kConsole);

  j["operator"] = {{"type", "person"}};
  EXPECT_THAT(ErrorOf(j), AllOf(HasSubstr("$.operator.type"), HasSubstr("virtual_fixture")));
  j = Example();
  j["operator"]["port"]["path"] = j["units"][0]["port"]["path"];
  EXPECT_THAT(ErrorOf(j), AllOf(HasSubstr("$.operator"), HasSubstr("already used")));
  j = Example();
  j["operator"].erase("port");
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.operator"));
}

TEST(Station, RoundTripsThroughJson) {
  const Station st = Station::Load(kExample);
  const nlohmann::json j = st.ToJson();
  EXPECT_EQ(Station::FromJson(common::ParamReader(j, "again")).ToJson(), j);
}

TEST(Station, RefusesWhatARealLabWouldGetWrong) {
  nlohmann::json j = Example();
  j["units"][1]["port"]["parity"] = "X";
  EXPECT_THAT(ErrorOf(j),
              AllOf(HasSubstr("$.units[1].port.parity"), HasSubstr("\"N\", \"E\" or \"O\"")));

  j = Example();
  j["units"][1]["port"]["path"] = j["units"][0]["port"]["path"];
  EXPECT_THAT(ErrorOf(j), AllOf(HasSubstr("$.units[1]"), HasSubstr("already used")));

  // One device under two names: a symlink and its target, and a path spelt two ways.
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("adahrs_station_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::filesystem::remove(dir / "imu1");
  std::filesystem::create_symlink("/dev/null", dir / "imu1");
  j = Example();
  j["units"][0]["port"]["path"] = (dir / "imu1").string();
  j["units"][1]["port"]["path"] = "/dev/null";
  EXPECT_THAT(ErrorOf(j),
              AllOf(HasSubstr("$.units[1].port.path"),
                    HasSubstr("/dev/null is the device"),
                    HasSubstr("imu1 already used")));
  j["units"][1]["port"]["path"] = (dir / "." / "imu1").string();
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.units[1].port.path"));
  std::filesystem::remove_all(dir);
  j = Example();
  j["units"][1]["port"]["path"] = "/dev/not_yet_a/../not_yet_b";
  j["units"][0]["port"]["path"] = "/dev/not_yet_b";
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.units[1].port.path"));

  // Two IMUs in one slot of the fixture.
  j = Example();
  j["units"][1]["slot"] = j["units"][0]["slot"];
  EXPECT_THAT(ErrorOf(j),
              AllOf(HasSubstr("$.units[1].slot"), HasSubstr("slot 1 already holds imu1")));

  j = Example();
  j["instruments"]["imu_chamber"]["type"] = "watlow_942";
  EXPECT_THAT(ErrorOf(j),
              AllOf(HasSubstr("$.instruments.imu_chamber.type"), HasSubstr("watlow_f4")));

  j = Example();
  j["instruments"]["rate_tabel"] = j["instruments"]["rate_table"];
  EXPECT_THAT(ErrorOf(j), AllOf(HasSubstr("$.instruments.rate_tabel"), HasSubstr("unknown key")));

  j = Example();
  for (int i = 0; i < 3; ++i) {
    nlohmann::json u = j["units"][0];
    u["role"] = "imu" + std::to_string(3 + i);
    u["slot"] = std::min(4, 3 + i);
    u["port"]["path"] = "/dev/x" + std::to_string(i);
    j["units"].push_back(u);
  }
  EXPECT_THAT(ErrorOf(j), AllOf(HasSubstr("$.units[4]"), HasSubstr("at most 4 IMU")));

  j = Example();
  j["time_scale"] = 0;
  EXPECT_THAT(ErrorOf(j), AllOf(HasSubstr("$.time_scale"), HasSubstr("out of range")));
}

TEST(Station, InstrumentLimitsAreTypedAndOptional) {
  // The example declares the table's and the F4's limits (docs/station.md "Limits").
  const Station st = Station::Load(kExample);
  const InstrumentLimits& table = st.Instrument("rate_table")->limits;
  EXPECT_EQ(table.max_rate_dps, 360.0);
  EXPECT_EQ(table.max_accel_dps2, 500.0);
  EXPECT_FALSE(table.min_c.has_value());
  const InstrumentLimits& chamber = st.Instrument("imu_chamber")->limits;
  EXPECT_EQ(chamber.min_c, -70.0);
  EXPECT_EQ(chamber.max_c, 180.0);
  EXPECT_EQ(chamber.max_ramp_c_per_min, 3.5);
  EXPECT_EQ(chamber.heat_rate_c_per_min, 5.0);
  EXPECT_EQ(chamber.cool_rate_c_per_min, 3.5);

  // Missing: every limit unset (the pipeline's defaults apply), and none written back.
  nlohmann::json j = Example();
  j["instruments"]["imu_chamber"].erase("limits");
  j["instruments"]["rate_table"]["limits"] = {{"max_accel_dps2", 200.0}};
  const Station partial = Station::FromJson(common::ParamReader(j, "station.json"));
  const InstrumentLimits& none = partial.Instrument("imu_chamber")->limits;
  EXPECT_FALSE(none.min_c || none.max_c || none.max_ramp_c_per_min || none.heat_rate_c_per_min ||
               none.cool_rate_c_per_min);
  EXPECT_FALSE(partial.Instrument("rate_table")->limits.max_rate_dps.has_value());
  EXPECT_EQ(partial.Instrument("rate_table")->limits.max_accel_dps2, 200.0);
  const nlohmann::json back = partial.ToJson();
  EXPECT_FALSE(back["instruments"]["imu_chamber"].contains("limits"));
  EXPECT_EQ(back["instruments"]["rate_table"]["limits"],
            nlohmann::json({{"max_accel_dps2", 200.0}}));
  EXPECT_EQ(Station::FromJson(common::ParamReader(back, "again")).ToJson(), back);
}

TEST(Station, RefusesMalformedLimitsNamingThePath) {
  nlohmann::json j = Example();
  j["instruments"]["imu_chamber"]["limits"]["max_rate_dps"] = 100.0;  // a table's key
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.instruments.imu_chamber.limits.max_rate_dps"));
  j = Example();
  j["instruments"]["imu_chamber"]["limits"].erase("min_c");
  EXPECT_THAT(ErrorOf(j),
              AllOf(HasSubstr("$.instruments.imu_chamber.limits.min_c"), HasSubstr("together")));
  j = Example();
  j["instruments"]["imu_chamber"]["limits"]["min_c"] = 200.0;
  EXPECT_THAT(ErrorOf(j),
              AllOf(HasSubstr("$.instruments.imu_chamber.limits.max_c"), HasSubstr("not above")));
  j = Example();
  j["instruments"]["imu_chamber"]["limits"]["max_ramp_c_per_min"] = "fast";
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.instruments.imu_chamber.limits.max_ramp_c_per_min"));
  j = Example();
  j["instruments"]["rate_table"]["limits"]["max_rate_dps"] = 0.0;
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.instruments.rate_table.limits.max_rate_dps"));
  j = Example();
  j["instruments"]["rate_table"]["limits"] = 5;
  EXPECT_THAT(ErrorOf(j), HasSubstr("$.instruments.rate_table.limits"));
}

}  // namespace
}  // namespace adahrs::hil
