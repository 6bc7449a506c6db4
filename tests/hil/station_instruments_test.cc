// OpenStation against the virtual rig as a separate process: every role of a station file opened
// through the one code path the executor uses, and the virtual fixture operator moving the rig's
// fixture.
#include "hil/drivers/station_instruments.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../support/rig_process.h"
#include "hil/drivers/unit_serial.h"

namespace adahrs::hil {
namespace {

using ::testing::HasSubstr;

constexpr double kTimeScale = 200.0;

TEST(OpenStation, OpensEveryUnitOfTheStationInOrder) {
  testing::RigProcess rig(kTimeScale);
  const Station station = Station::Load(rig.WriteStation());
  ScaledClock clock(kTimeScale);
  StationInstruments instruments = OpenStation(station, clock);
  ASSERT_EQ(instruments.units.size(), rig.manifest()["units"].size());
  for (size_t i = 0; i < instruments.units.size(); ++i) {
    const nlohmann::json& truth = rig.manifest()["units"][i];
    UnitLink& link = *instruments.units[i];
    EXPECT_EQ(link.entry().role, truth["role"].get<std::string>());
    EXPECT_EQ(UnitSerialText(link.entry().kind, link.Identify().serial_number),
              truth["serial"].get<std::string>());
  }
  ASSERT_NE(instruments.op, nullptr);
}

TEST(VirtualFixtureOperator, MountMovesTheRigsFixture) {
  testing::RigProcess rig(kTimeScale);
  const Station station = Station::Load(rig.WriteStation());
  ScaledClock clock(kTimeScale);
  StationInstruments instruments = OpenStation(station, clock);
  instruments.op->Mount({"imu1", "imu3"}, 12);
  // Read back through the rig's own control port: the fixture, not the operator, is the truth.
  EXPECT_EQ(rig.Control("orientation imu1"), "OK imu1 12");
  EXPECT_EQ(rig.Control("orientation imu2"), "OK imu2 31");  // the default config's start code
  EXPECT_EQ(rig.Control("orientation imu3"), "OK imu3 12");
  instruments.op->Prompt("check the fixture bolts");
  try {
    instruments.op->Mount({"imu9"}, 11);
    FAIL() << "the fixture mounted a unit the rig does not have";
  } catch (const InstrumentError& e) {
    EXPECT_EQ(e.kind(), InstrumentError::Kind::kRefused);
    EXPECT_EQ(e.role(), "operator");
    EXPECT_EQ(e.command(), "orientation imu9 11");
    EXPECT_THAT(e.reply(), HasSubstr("ERR"));
  }
}

TEST(OpenStation, AMissingPortIsNamedWithItsRole) {
  testing::RigProcess rig(kTimeScale);
  const Station station = Station::Load(rig.WriteStation("station.json", [](nlohmann::json& j) {
    j["units"][0]["port"]["path"] = "/nonexistent/imu1";
  }));
  ScaledClock clock(kTimeScale);
  try {
    OpenStation(station, clock);
    FAIL() << "a missing port was opened";
  } catch (const InstrumentError& e) {
    EXPECT_EQ(e.role(), "imu1");
    EXPECT_EQ(e.port(), "/nonexistent/imu1");
  }
}

}  // namespace
}  // namespace adahrs::hil
