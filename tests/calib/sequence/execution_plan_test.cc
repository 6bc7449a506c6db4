#include "calib/sequence/execution_plan.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/sequence/validation.h"

namespace adahrs::calib {
namespace {

using ::testing::ElementsAre;
using ::testing::ElementsAreArray;
using ::testing::HasSubstr;

std::vector<std::string> Descriptions(const ExecutionPlan& plan) {
  std::vector<std::string> lines;
  for (const PlannedAction& a : plan.actions) lines.push_back(Describe(a.action));
  return lines;
}

Sequence Imu(std::vector<Step> steps) {
  Sequence s;
  s.name = "t";
  s.unit_kind = UnitKind::kImu;
  s.steps = std::move(steps);
  return s;
}

TEST(GyroRates, ReferenceSweepGivesExactlyTheSevenReferenceRates) {
  // reference-method.md Method 4: −150, −100, −50, 0, 50, 100, 150 °/s, exactly.
  EXPECT_THAT(GyroRates_dps(GyroStep{11, 1, -150.0, 150.0, 50.0, 100.0}),
              ElementsAre(-150.0, -100.0, -50.0, 0.0, 50.0, 100.0, 150.0));
  // One rate when min = max; 0…1 by 0.1 gives eleven rates ending at exactly 1.
  EXPECT_THAT(GyroRates_dps(GyroStep{11, 1, 30.0, 30.0, 10.0, 100.0}), ElementsAre(30.0));
  const std::vector<double> tenths = GyroRates_dps(GyroStep{11, 1, 0.0, 1.0, 0.1, 100.0});
  ASSERT_EQ(tenths.size(), 11u);
  EXPECT_DOUBLE_EQ(tenths.back(), 1.0);
}

TEST(EffectiveTags, ExplicitKeptAndSmallestFreeAssignedInOrder) {
  const Sequence s = Imu({{std::nullopt, AccelStep{11, 1}},
                          {2, AccelStep{12, 1}},
                          {std::nullopt, AccelStep{21, 1}},
                          {std::nullopt, AccelStep{22, 1}},
                          {1, AccelStep{31, 1}}});
  // 1 and 2 are taken explicitly, so the free steps get 3, 4, 5.
  EXPECT_THAT(EffectiveTags(s), ElementsAre(3, 2, 4, 5, 1));
}

TEST(ExecutionPlan, GyroStepExpandsToRateCommandsWithAcquisitions) {
  const Sequence s = Imu({{9, GyroStep{21, 200, -100.0, 100.0, 100.0, 50.0}}});
  PlanTiming timing;
  timing.operator_prompt_s = 30.0;
  const ExecutionPlan plan = ExpandSequence(s, {}, timing);
  EXPECT_THAT(Descriptions(plan),
              ElementsAre("mount batch in orientation 21",
                          "interlock: jog 100 deg/s, check gyro axis for orientation 21",
                          "set table rate -100 deg/s (accel 50 deg/s^2)",
                          "wait table at -100 deg/s",
                          "acquire 200 packets",
                          "set table rate 0 deg/s (accel 50 deg/s^2)",
                          "wait table at 0 deg/s",
                          "acquire 200 packets",
                          "set table rate 100 deg/s (accel 50 deg/s^2)",
                          "wait table at 100 deg/s",
                          "acquire 200 packets",
                          "stop table"));
  for (const PlannedAction& a : plan.actions) {
    EXPECT_EQ(a.step, 0u);
    EXPECT_EQ(a.tag, 9);
  }
  // Hand sum: mount 30; jog check 2·100/50 + settle 2 + sample 1 = 7; ramps 100/50, 100/50,
  // 100/50 and stop 100/50 = 8; three settles 6; three acquisitions of 200 packets at 100 Hz = 6.
  EXPECT_DOUBLE_EQ(plan.duration_estimate_s, 30.0 + 7.0 + 8.0 + 6.0 + 6.0);
}

TEST(ExecutionPlan, MountOnlyWhenOrientationChanges) {
  const Sequence s = Imu({{std::nullopt, AccelStep{31, 100}},
                          {std::nullopt, AccelStep{31, 100}},
                          {std::nullopt, AccelStep{11, 100}}});
  EXPECT_THAT(Descriptions(ExpandSequence(s, {})),
              ElementsAre("mount batch in orientation 31",
                          "interlock: check gravity for orientation 31",
                          "acquire 100 packets",
                          "interlock: check gravity for orientation 31",
                          "acquire 100 packets",
                          "mount batch in orientation 11",
                          "interlock: check gravity for orientation 11",
                          "acquire 100 packets"));
}

TEST(ExecutionPlan, CrossAxisVisitsElevenTwentyOneThirtyOneAtRestAndAtRate) {
  const ExecutionPlan plan =
      ExpandSequence(Imu({{std::nullopt, CrossAxisStep{50, 150.0, 100.0}}}), {});
  std::vector<std::string> expected;
  for (int o : {11, 21, 31}) {
    const std::string code = std::to_string(o);
    for (const std::string& line :
         {"mount batch in orientation " + code,
          "interlock: check gravity for orientation " + code,
          std::string("acquire 50 packets"),
          "interlock: jog 100 deg/s, check gyro axis for orientation " + code,
          std::string("set table rate 150 deg/s (accel 100 deg/s^2)"),
          std::string("wait table at 150 deg/s"),
          std::string("acquire 50 packets"),
          std::string("stop table")}) {
      expected.push_back(line);
    }
  }
  EXPECT_THAT(Descriptions(plan), ElementsAreArray(expected));
}

TEST(ExecutionPlan, ChamberAndAdtsSteps) {
  PlanTiming timing;
  timing.initial_chamber_c = 25.0;
  timing.chamber_ramp_c_per_min = 1.0;
  Sequence s;
  s.name = "ads";
  s.unit_kind = UnitKind::kAds;
  s.steps = {{std::nullopt, TargetTemperatureStep{-15.0, 1.0, 600.0}},
             {std::nullopt, AltitudeStep{3000.0, 1500.0}},
             {std::nullopt, LogStep{300, std::nullopt}},
             {std::nullopt, AirspeedStep{100.0, 50.0}},
             {std::nullopt, LogStep{std::nullopt, 5.0}}};
  const ExecutionPlan plan = ExpandSequence(s, {}, timing);
  EXPECT_THAT(Descriptions(plan),
              ElementsAre("set chamber set point -15 degC",
                          "wait chamber within -15 ± 1 degC, soak 600 s",
                          "set ADTS altitude 3000 ft at 1500 ft/min",
                          "wait ADTS stable",
                          "acquire 300 packets",
                          "set ADTS airspeed 100 kt at 50 kt/min",
                          "wait ADTS stable",
                          "log for 5 s"));
  // 40 °C at 1 °C/min = 2400 s + 600 s soak; 3000 ft at 1500 ft/min = 120 s + 15 s stable;
  // 3 s of packets; 100 kt at 50 kt/min = 120 s + 15 s; 5 s of logging.
  EXPECT_DOUBLE_EQ(plan.duration_estimate_s, 3000.0 + 135.0 + 3.0 + 135.0 + 5.0);
  // The executor bounds every wait by its estimate, so the slew belongs to the wait, not to the
  // command that returns at once (a 5,000 ft step at 3,000 ft/min once timed out at 105 s of a
  // 115 s wait when the command carried the slew).
  EXPECT_DOUBLE_EQ(plan.actions[2].estimate_s, 0.0);
  EXPECT_DOUBLE_EQ(plan.actions[3].estimate_s, 135.0);
  EXPECT_DOUBLE_EQ(plan.actions[5].estimate_s, 0.0);
  EXPECT_DOUBLE_EQ(plan.actions[6].estimate_s, 135.0);
}

TEST(ProfileDuration, JumpRepeatsItsLoopCountTimes) {
  // 25 → −40 at 2 °C/min: 1950 s; soak 1800; −40 → 85: 3750; soak 1800 (first pass 9300 s).
  // The jump repeats steps 1–4 twice more from 85 °C: 2 × (3750 + 1800 + 3750 + 1800) = 22200.
  // Then 85 → 25 at 2 °C/min: 1800 s. Total 33300 s.
  const ThermalProfileStep profile{"BURN",
                                   {F4RampRate{-40.0, 2.0},
                                    F4Soak{1800.0},
                                    F4RampRate{85.0, 2.0},
                                    F4Soak{1800.0},
                                    F4Jump{1, 2},
                                    F4RampRate{25.0, 2.0},
                                    F4End{}}};
  EXPECT_DOUBLE_EQ(ProfileDurationS(profile, 25.0), 33300.0);
}

TEST(ProfileDuration, NestedLoopRunsInnerLoopInFullEachOuterPass) {
  // Inner: soak 10 s then jump to it once more (2 × 10 s per pass). Outer: ramp-time 100 s, the
  // inner loop, jump to step 1 twice more: 3 passes × (100 + 20) = 360 s.
  const ThermalProfileStep profile{
      "NEST", {F4RampTime{30.0, 100.0}, F4Soak{10.0}, F4Jump{2, 1}, F4Jump{1, 2}, F4End{}}};
  EXPECT_DOUBLE_EQ(ProfileDurationS(profile, 25.0), 360.0);
}

TEST(ExecutionPlan, ProfileIsDownloadedThenRunWhileLogging) {
  PlanTiming timing;
  timing.profile_download_s = 10.0;
  const Sequence s =
      Imu({{std::nullopt, ThermalProfileStep{"T", {F4RampTime{30.0, 100.0}, F4End{}}}}});
  const ExecutionPlan plan = ExpandSequence(s, {}, timing);
  EXPECT_THAT(Descriptions(plan),
              ElementsAre("download chamber profile \"T\" (2 steps)",
                          "run chamber profile \"T\", logging until its end"));
  EXPECT_DOUBLE_EQ(plan.duration_estimate_s, 110.0);
}

TEST(ExecutionPlan, InvalidSequenceIsNotExpanded) {
  const Sequence s = Imu({{std::nullopt, GyroStep{11, 10, -300.0, 300.0, 300.0, 100.0}}});
  try {
    ExpandSequence(s, {});
    FAIL() << "no exception";
  } catch (const SequenceError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("sequence t: $.steps[0].rate_max_dps"));
  }
}

}  // namespace
}  // namespace adahrs::calib
