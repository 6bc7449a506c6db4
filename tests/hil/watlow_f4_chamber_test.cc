// The Watlow F4 driver (libmodbus master) against the virtual F4 of the rig process
// (docs/rig/watlow-f4.md).
#include "hil/drivers/watlow_f4_chamber.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "driver_test_util.h"

namespace adahrs::hil {
namespace {

using test::RigStation;
using ::testing::HasSubstr;

TEST(WatlowF4Chamber, SetPointIsWrittenAndTheChamberFollows) {
  RigStation s;
  WatlowF4Chamber chamber(s.Entry("imu_chamber"), s.clock);
  EXPECT_THAT(chamber.Identify().detail, HasSubstr("1 implied decimal"));
  // Power-on air 25 degC (rig config initial_air_c) within the ±0.3 degC control cycling and the
  // 0.1 degC register resolution.
  EXPECT_NEAR(chamber.ReadProcessC(), 25.0, 0.4);
  chamber.SetSetPointC(31.5);
  EXPECT_DOUBLE_EQ(chamber.ReadSetPointC(), 31.5);
  // 6.5 degC at the 5 degC/min heating capacity, then the 120 s exponential tail: within the
  // control band a few simulated minutes later.
  EXPECT_TRUE(
      test::WaitUntil(s.clock, [&] { return std::abs(chamber.ReadProcessC() - 31.5) < 0.5; }));
  // The rig's own air temperature agrees (the driver reads what the world holds).
  EXPECT_NEAR(test::EnvValue(s.rig, "imu_chamber_air_c"), 31.5, 0.6);
}

TEST(WatlowF4Chamber, DownloadedProfileRunsToItsEnd) {
  RigStation s;
  WatlowF4Chamber chamber(s.Entry("imu_chamber"), s.clock);
  const std::vector<F4ProfileStep> steps = {
      F4RampTime{30.0, 120.0}, F4Soak{60.0}, F4RampRate{28.0, 2.0}, F4End{F4EndAction::kHold, 0.0}};
  chamber.DownloadProfile("drv test", steps);
  // Downloading again under the same name replaces the profile (no second copy to start).
  chamber.DownloadProfile("drv test", steps);
  const double start_s = s.clock.NowS();
  chamber.StartProfile("drv test");
  EXPECT_TRUE(chamber.ProfileRunning());
  // Half-way through the 120 s ramp from the PV (~25 degC) the set point is between 25 and 30.
  s.clock.SleepS(60.0);
  const double mid_c = chamber.ReadSetPointC();
  EXPECT_GT(mid_c, 25.5);
  EXPECT_LT(mid_c, 29.5);
  // 120 s ramp + 60 s soak + 1 min ramp down at 2 degC/min = 240 s of profile.
  ASSERT_TRUE(test::WaitUntil(s.clock, [&] { return !chamber.ProfileRunning(); }));
  EXPECT_GT(s.clock.NowS() - start_s, 230.0);
  // End action hold: static mode at the last set point.
  EXPECT_DOUBLE_EQ(chamber.ReadSetPointC(), 28.0);
}

TEST(WatlowF4Chamber, HoldStopsARunningProfileAtItsPresentSetPoint) {
  RigStation s;
  WatlowF4Chamber chamber(s.Entry("imu_chamber"), s.clock);
  chamber.DownloadProfile("HOLDME", {F4RampTime{45.0, 600.0}, F4End{}});
  chamber.StartProfile("HOLDME");
  s.clock.SleepS(120.0);
  chamber.Hold();
  EXPECT_FALSE(chamber.ProfileRunning());
  const double held_c = chamber.ReadSetPointC();
  EXPECT_GT(held_c, 26.0);  // 20 degC in 600 s: about 4 degC after 120 s
  EXPECT_LT(held_c, 35.0);
  s.clock.SleepS(60.0);
  EXPECT_DOUBLE_EQ(chamber.ReadSetPointC(), held_c);
}

TEST(WatlowF4Chamber, SetPointBeyondTheLimitIsRefusedWithTheExceptionCode) {
  RigStation s;
  WatlowF4Chamber chamber(s.Entry("imu_chamber"), s.clock);
  try {
    chamber.SetSetPointC(200.0);  // high limit 180.0 degC (register 603)
    FAIL() << "the F4 accepted 200 degC";
  } catch (const InstrumentError& e) {
    EXPECT_EQ(e.kind(), InstrumentError::Kind::kRefused);
    EXPECT_EQ(e.command(), "write register 300 = 2000");
    EXPECT_THAT(e.reply(), HasSubstr("exception 03"));
    EXPECT_THAT(e.what(), HasSubstr("imu_chamber on " + s.rig.Port("imu_chamber")));
  }
}

TEST(WatlowF4Chamber, SilentControllerIsNoReplyAfterTheBoundedRetries) {
  RigStation s;
  WatlowF4Chamber chamber(s.Entry("imu_chamber"), s.clock);
  ASSERT_EQ(s.rig.Control("fault imu_chamber silent on"), "OK imu_chamber silent on");
  try {
    chamber.ReadProcessC();
    FAIL() << "a silent F4 answered";
  } catch (const InstrumentError& e) {
    EXPECT_EQ(e.kind(), InstrumentError::Kind::kNoReply);
    EXPECT_EQ(e.role(), "imu_chamber");
    EXPECT_EQ(e.command(), "read register 100 (x2)");  // PV and input error
    EXPECT_THAT(e.what(), HasSubstr("3 attempts"));
  }
}

}  // namespace
}  // namespace adahrs::hil
