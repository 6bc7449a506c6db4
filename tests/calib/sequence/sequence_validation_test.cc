#include "calib/sequence/validation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/sequence/sequence_json.h"
#include "tests/calib/sequence/sequence_test_util.h"

namespace adahrs::calib {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using testing::Joined;
using ::testing::SizeIs;
using testing::TempFile;

Sequence Imu(std::vector<Step> steps) {
  Sequence s;
  s.name = "t";
  s.unit_kind = UnitKind::kImu;
  s.steps = std::move(steps);
  return s;
}

Sequence Ads(std::vector<Step> steps) {
  Sequence s = Imu(std::move(steps));
  s.unit_kind = UnitKind::kAds;
  return s;
}

ThermalProfileStep Profile(std::vector<F4ProfileStep> steps) {
  return ThermalProfileStep{"CAL", std::move(steps)};
}

// The single problem of `sequence` under `limits`, or a failure listing them all.
SequenceProblem OnlyProblem(const Sequence& sequence, const SequenceLimits& limits = {}) {
  const std::vector<SequenceProblem> problems = ValidateSequence(sequence, limits);
  EXPECT_THAT(problems, SizeIs(1)) << Joined(problems, "seq.json");
  return problems.empty() ? SequenceProblem{} : problems.front();
}

TEST(SequenceValidation, ValidStepsOfEveryKindPass) {
  const Sequence imu = Imu({{1, PromptStep{"mount"}},
                            {std::nullopt, TargetTemperatureStep{25.0, 0.5, 600.0}},
                            {std::nullopt, AccelStep{12, 100}},
                            {std::nullopt, GyroStep{21, 100, -150.0, 150.0, 50.0, 100.0}},
                            {std::nullopt, CrossAxisStep{100, 150.0, 100.0}},
                            {std::nullopt,
                             Profile({F4RampRate{-40.0, 2.0},
                                      F4Soak{60.0},
                                      F4RampTime{85.0, 7500.0},
                                      F4Jump{1, 3},
                                      F4End{}})}});
  EXPECT_THAT(ValidateSequence(imu, {}), IsEmpty()) << Joined(ValidateSequence(imu, {}), "imu");
  const Sequence ads = Ads({{std::nullopt, AltitudeStep{-1000.0, 3000.0}},
                            {std::nullopt, LogStep{100, std::nullopt}},
                            {std::nullopt, AirspeedStep{450.0, 100.0}},
                            {std::nullopt, LogStep{std::nullopt, 10.0}}});
  EXPECT_THAT(ValidateSequence(ads, {}), IsEmpty()) << Joined(ValidateSequence(ads, {}), "ads");
}

TEST(SequenceValidation, RateBeyondGyroRangeNamesTheLimit) {
  // ±200 °/s is within the table's ±360 but beyond the ADXRS150's ±150 °/s.
  const SequenceProblem p =
      OnlyProblem(Imu({{std::nullopt, GyroStep{11, 100, -150.0, 200.0, 50.0, 100.0}}}));
  EXPECT_EQ(p.path, "$.steps[0].rate_max_dps");
  EXPECT_THAT(p.rule, HasSubstr("rate 200 deg/s beyond the unit's gyro range"));
  EXPECT_EQ(p.limit, "unit gyro range ±150 deg/s");
}

TEST(SequenceValidation, RateBeyondTableLimitNamesTheTable) {
  // A station whose table is limited to 100 °/s: the 150 °/s cross-axis rate exceeds it only.
  SequenceLimits limits;
  limits.table_name = "rate table (Aero 812)";
  limits.table_max_rate_dps = 100.0;
  const SequenceProblem p =
      OnlyProblem(Imu({{std::nullopt, CrossAxisStep{10, 150.0, 100.0}}}), limits);
  EXPECT_EQ(p.path, "$.steps[0].rate_dps");
  EXPECT_EQ(p.limit, "rate table (Aero 812) ±100 deg/s");
}

TEST(SequenceValidation, TableAccelerationBeyondLimit) {
  const SequenceProblem p =
      OnlyProblem(Imu({{std::nullopt, GyroStep{11, 100, 0.0, 100.0, 50.0, 600.0}}}));
  EXPECT_EQ(p.path, "$.steps[0].table_accel_dps2");
  EXPECT_EQ(p.limit, "rate table acceleration 500 deg/s^2");
}

TEST(SequenceValidation, GyroRatesMustBeAWholeNumberOfIncrements) {
  const SequenceProblem p =
      OnlyProblem(Imu({{std::nullopt, GyroStep{11, 100, -150.0, 150.0, 40.0, 100.0}}}));
  EXPECT_EQ(p.path, "$.steps[0].rate_increment_dps");
  EXPECT_THAT(p.rule, HasSubstr("not a whole number of 40 deg/s increments"));
  // Decimal increments that are inexact in binary are whole: 0…1 by 0.1 is ten increments (on a
  // table that takes rates in 0.1 deg/s steps).
  SequenceLimits fine_table;
  fine_table.table_rate_resolution_dps = 0.1;
  EXPECT_THAT(
      ValidateSequence(Imu({{std::nullopt, GyroStep{11, 1, 0.0, 1.0, 0.1, 100.0}}}), fine_table),
      IsEmpty());
}

TEST(SequenceValidation, GyroRatesMustBeWholeStepsOfTheTable) {
  // The ATL's JOG takes integer deg/s: -125…+125 by 62.5 would command -62.5 deg/s.
  const SequenceProblem p =
      OnlyProblem(Imu({{std::nullopt, GyroStep{11, 100, -125.0, 125.0, 62.5, 100.0}}}));
  EXPECT_EQ(p.path, "$.steps[0].rate_increment_dps");
  EXPECT_THAT(p.rule,
              HasSubstr("62.5 deg/s is not a multiple of the rate table's rate resolution"));
  EXPECT_EQ(p.limit, "rate table commands rates in steps of 1 deg/s");
  const SequenceProblem cross = OnlyProblem(Imu({{std::nullopt, CrossAxisStep{10, 100.5, 100.0}}}));
  EXPECT_EQ(cross.path, "$.steps[0].rate_dps");
  // An increment below the table's step passed the multiple-of-resolution test (1e-9 is 0 steps
  // to within 1e-9) and expanded into 3e11 rates.
  const SequenceProblem tiny =
      OnlyProblem(Imu({{std::nullopt, GyroStep{11, 100, -150.0, 150.0, 1e-9, 100.0}}}));
  EXPECT_EQ(tiny.path, "$.steps[0].rate_increment_dps");
  EXPECT_THAT(tiny.rule, HasSubstr("below the rate table's rate resolution"));
  SequenceLimits fine_table;
  fine_table.table_rate_resolution_dps = 0.001;
  const SequenceProblem many =
      OnlyProblem(Imu({{std::nullopt, GyroStep{11, 100, -150.0, 150.0, 0.01, 100.0}}}), fine_table);
  EXPECT_THAT(many.rule, HasSubstr("30001 rates"));
  EXPECT_EQ(many.limit, "at most 1000 rates in one gyro step");
}

TEST(SequenceValidation, TemperatureBeyondUnitRatingAndChamberRange) {
  // 90 °C: beyond the unit's +85 °C rating, inside the chamber's +180 °C.
  SequenceProblem p = OnlyProblem(Imu({{std::nullopt, TargetTemperatureStep{90.0, 1.0, 0.0}}}));
  EXPECT_EQ(p.path, "$.steps[0].target_c");
  EXPECT_EQ(p.limit, "unit rating -40…85 degC");
  // A chamber that only reaches −30 °C refuses −40 °C, which the unit is rated for.
  SequenceLimits limits;
  limits.chamber_min_c = -30.0;
  p = OnlyProblem(Imu({{std::nullopt, TargetTemperatureStep{-40.0, 1.0, 0.0}}}), limits);
  EXPECT_THAT(p.rule, HasSubstr("beyond the chamber (Watlow F4)'s range"));
  EXPECT_EQ(p.limit, "chamber (Watlow F4) -30…180 degC");
}

TEST(SequenceValidation, AltitudeOutsideUnitRangeAndStaticPressureLimit) {
  SequenceProblem p = OnlyProblem(Ads({{std::nullopt, AltitudeStep{51000.0, 3000.0}}}));
  EXPECT_EQ(p.path, "$.steps[0].alt_ft");
  EXPECT_EQ(p.limit, "unit altitude -1000…50000 ft");
  // With the rated 15 psi as the static limit, −1,000 ft is refused: ISA gives 1050.41 hPa
  // = 15.235 psi there (physics.md §4.1 table).
  SequenceLimits limits;
  limits.ads_static_max_pa = common::PsiToPa(15.0);
  p = OnlyProblem(Ads({{std::nullopt, AltitudeStep{-1000.0, 3000.0}}}), limits);
  EXPECT_THAT(p.rule, HasSubstr("static pressure of 105041 Pa (15.235 psi)"));
  EXPECT_EQ(p.limit, "ADS static pressure 103421 Pa (15.000 psi)");
}

TEST(SequenceValidation, SlewBeyondUnitSafeRate) {
  const SequenceProblem p = OnlyProblem(Ads({{std::nullopt, AltitudeStep{10000.0, 8000.0}}}));
  EXPECT_EQ(p.path, "$.steps[0].rate_ft_per_min");
  EXPECT_THAT(p.rule, HasSubstr("altitude rate must be in (0, 6000] ft/min, got 8000"));
  EXPECT_THAT(p.limit, HasSubstr("ADS safe slew 6000 ft/min"));
  const SequenceProblem q = OnlyProblem(Ads({{std::nullopt, AirspeedStep{100.0, 0.0}}}));
  EXPECT_EQ(q.path, "$.steps[0].rate_kt_per_min");
}

TEST(SequenceValidation, AirspeedBeyondUnitAndPitotLimit) {
  // 500 kt: beyond the unit's 450 kt; inside the ADTS's 850 kt; qc(500 kt) = 44.0 kPa < 15 psi.
  SequenceProblem p = OnlyProblem(Ads({{std::nullopt, AirspeedStep{500.0, 100.0}}}));
  EXPECT_EQ(p.limit, "unit airspeed 0…450 kt");
  // A 5 psid pitot sensor (34.5 kPa) cannot take 450 kt: qc = 36,801 Pa (physics.md §4.1).
  SequenceLimits limits;
  limits.ads_pitot_max_pa = common::PsiToPa(5.0);
  p = OnlyProblem(Ads({{std::nullopt, AirspeedStep{450.0, 100.0}}}), limits);
  EXPECT_THAT(p.rule, HasSubstr("impact pressure of 36801 Pa"));
  EXPECT_EQ(p.limit, "ADS pitot pressure 34474 Pa");
}

TEST(SequenceValidation, DuplicateTagsRefused) {
  const Sequence s =
      Imu({{5, AccelStep{11, 10}}, {std::nullopt, AccelStep{12, 10}}, {5, AccelStep{21, 10}}});
  const SequenceProblem p = OnlyProblem(s);
  EXPECT_EQ(p.path, "$.steps[2].tag");
  EXPECT_EQ(p.rule, "TAG 5 already used by $.steps[0]");
  EXPECT_THROW(EffectiveTags(s), std::invalid_argument);
}

// More steps than TAGs: the unstated ones start over after 255, skipping stated ones, and no two
// consecutive steps share a TAG; with a single TAG left to assign two adjacent unstated steps
// would, and the sequence is refused naming the step.
TEST(SequenceValidation, TagsStartOverBeyond255StepsButNeverRepeatBackToBack) {
  std::vector<Step> steps;
  steps.push_back({7, AccelStep{11, 10}});
  for (int i = 0; i < 300; ++i) steps.push_back({std::nullopt, AccelStep{11, 10}});
  const Sequence s = Imu(steps);
  EXPECT_TRUE(ValidateSequence(s, {}).empty()) << Joined(ValidateSequence(s, {}), "seq.json");
  const std::vector<uint8_t> tags = EffectiveTags(s);
  ASSERT_EQ(tags.size(), 301u);
  EXPECT_EQ(tags[0], 7);
  EXPECT_EQ(tags[1], 1);
  EXPECT_EQ(tags[7], 8);      // 7 is stated: skipped
  EXPECT_EQ(tags[254], 255);  // the 254 free TAGs used once each
  EXPECT_EQ(tags[255], 1);    // then again from the first
  for (size_t i = 1; i < tags.size(); ++i) EXPECT_NE(tags[i], tags[i - 1]) << i;
  std::vector<Step> crowded;
  for (int t = 1; t <= 254; ++t) crowded.push_back({t, AccelStep{11, 10}});
  crowded.push_back({std::nullopt, AccelStep{11, 10}});
  crowded.push_back({std::nullopt, AccelStep{11, 10}});
  const SequenceProblem p = OnlyProblem(Imu(crowded));
  EXPECT_EQ(p.path, "$.steps");
  EXPECT_THAT(p.rule, HasSubstr("step 255: TAG 255 would follow itself"));
}

TEST(SequenceValidation, TagOutsideOneByteRefused) {
  EXPECT_EQ(OnlyProblem(Imu({{0, AccelStep{11, 10}}})).path, "$.steps[0].tag");
  EXPECT_THAT(OnlyProblem(Imu({{256, AccelStep{11, 10}}})).rule, HasSubstr("TAG 256 outside"));
}

TEST(SequenceValidation, ProfileJumpToLaterStepRefused) {
  const SequenceProblem p = OnlyProblem(
      Imu({{std::nullopt, Profile({F4RampRate{30.0, 1.0}, F4Jump{3, 1}, F4Soak{60.0}, F4End{}})}}));
  EXPECT_EQ(p.path, "$.steps[0].profile_steps[1].to_step");
  EXPECT_THAT(p.rule, HasSubstr("jump from step 2 to step 3: a jump goes back"));
}

TEST(SequenceValidation, ProfileJumpCountOutOfRangeRefused) {
  for (int count : {0, 10000}) {
    const SequenceProblem p = OnlyProblem(
        Imu({{std::nullopt, Profile({F4RampRate{30.0, 1.0}, F4Jump{1, count}, F4End{}})}}));
    EXPECT_EQ(p.path, "$.steps[0].profile_steps[1].count");
    EXPECT_EQ(p.limit, "chamber (Watlow F4) jump count 9999");
  }
}

TEST(SequenceValidation, ProfileShapeRules) {
  // No end step; jump onto a jump; bad name; too fast a ramp (25 → 85 °C in 10 min = 6 °C/min).
  const Sequence s =
      Imu({{std::nullopt, TargetTemperatureStep{25.0, 1.0, 0.0}},
           {std::nullopt,
            ThermalProfileStep{"cal-1", {F4RampTime{85.0, 600.0}, F4Jump{1, 1}, F4Jump{2, 1}}}}});
  const std::vector<SequenceProblem> problems = ValidateSequence(s, {});
  const std::string text = Joined(problems, "seq.json");
  EXPECT_THAT(problems, SizeIs(4)) << text;
  EXPECT_THAT(text,
              AllOf(HasSubstr("$.steps[1].profile_name: profile name \"cal-1\""),
                    HasSubstr("$.steps[1].profile_steps[2]: the last profile step must be "
                              "an end step"),
                    HasSubstr("$.steps[1].profile_steps[2].to_step: jump to step 2, a jump "
                              "step"),
                    HasSubstr("$.steps[1].profile_steps[0].duration_s: ramp from 25 to 85 "
                              "degC in 600 s is 6 degC/min")));
}

TEST(SequenceValidation, ProfileLongerThanTheChamberHoldsRefused) {
  // A chamber holding 24 steps, as the Watlow 942 does (protocols.md §3.6).
  SequenceLimits limits;
  limits.chamber_name = "chamber (Watlow 942)";
  limits.chamber_max_profile_steps = 24;
  std::vector<F4ProfileStep> steps(24, F4Soak{60.0});
  steps.push_back(F4End{});
  const SequenceProblem p = OnlyProblem(Imu({{std::nullopt, Profile(steps)}}), limits);
  EXPECT_EQ(p.path, "$.steps[0].profile_steps");
  EXPECT_EQ(p.limit, "chamber (Watlow 942) 24 profile steps");
}

TEST(SequenceValidation, AdsThermalProfileRefusedSinceThe942DriverRunsSetPointsOnly) {
  const SequenceProblem p =
      OnlyProblem(Ads({{std::nullopt, Profile({F4RampRate{-40.0, 2.0}, F4Soak{60.0}, F4End{}})}}));
  EXPECT_EQ(p.path, "$.steps[0].kind");
  EXPECT_THAT(p.rule, HasSubstr("chamber (Watlow 942) runs set points only"));
  EXPECT_EQ(p.limit, "chamber (Watlow 942) driver: set points only");
  SequenceLimits profiles;  // a bench whose ADS chamber driver ran profiles would take it
  profiles.ads_chamber_runs_profiles = true;
  EXPECT_THAT(ValidateSequence(Ads({{std::nullopt, Profile({F4Soak{60.0}, F4End{}})}}), profiles),
              IsEmpty());
}

TEST(SequenceValidation, StepKindMustSuitTheUnitKind) {
  const SequenceProblem p = OnlyProblem(Ads({{std::nullopt, AccelStep{11, 10}}}));
  EXPECT_EQ(p.path, "$.steps[0].kind");
  EXPECT_EQ(p.rule, "a accel step has no place in an ads sequence");
}

TEST(SequenceValidation, EveryProblemReportedAtOnce) {
  const Sequence s = Imu({{std::nullopt, AccelStep{13, 0}},
                          {std::nullopt, GyroStep{11, 10, -300.0, 300.0, 100.0, 100.0}},
                          {std::nullopt, TargetTemperatureStep{200.0, 0.0, -1.0}},
                          {std::nullopt, PromptStep{""}}});
  const std::string text = Joined(ValidateSequence(s, {}), "seq.json");
  // orientation, packets; rate_min and rate_max beyond the gyro range; temperature beyond unit
  // and chamber, band, soak; prompt text.
  EXPECT_THAT(ValidateSequence(s, {}), SizeIs(9)) << text;
  EXPECT_THAT(text,
              AllOf(HasSubstr("$.steps[0].orientation: orientation 13 is not"),
                    HasSubstr("$.steps[0].packets: packets must be 1…8640000, got 0"),
                    HasSubstr("$.steps[1].rate_min_dps"),
                    HasSubstr("$.steps[1].rate_max_dps"),
                    HasSubstr("(limit: unit rating -40…85 degC)"),
                    HasSubstr("(limit: chamber (Watlow F4) -70…180 degC)"),
                    HasSubstr("$.steps[2].band_c"),
                    HasSubstr("$.steps[2].soak_s"),
                    HasSubstr("$.steps[3].text")));
}

TEST(SequenceValidation, FileCheckReportsStructureAndLimitsTogether) {
  // Step 0 has an unknown key, step 1 a rate beyond the gyro range: both, with file paths.
  const TempFile file("mixed.json", R"({
    "format_version": 1, "name": "mixed", "description": "", "unit_kind": "imu",
    "steps": [
      {"kind": "accel", "orientation": 11, "packets": 10, "packet": 3},
      {"kind": "gyro", "orientation": 11, "packets": 10, "rate_min_dps": -160,
       "rate_max_dps": 160, "rate_increment_dps": 80, "table_accel_dps2": 100}]})");
  const std::vector<SequenceProblem> problems = CheckSequenceFile(file.path(), {});
  const std::string text = Joined(problems, file.path());
  EXPECT_THAT(problems, SizeIs(3)) << text;
  EXPECT_THAT(text,
              AllOf(HasSubstr(file.path() + ": $.steps[0].packet: unknown key"),
                    HasSubstr(file.path() + ": $.steps[1].rate_min_dps: rate -160 deg/s"),
                    HasSubstr(file.path() + ": $.steps[1].rate_max_dps: rate 160 deg/s")));
  try {
    LoadValidSequence(file.path(), {});
    FAIL() << "no exception";
  } catch (const SequenceError& e) {
    EXPECT_THAT(std::string(e.what()),
                AllOf(HasSubstr("sequence refused, 3 problems"),
                      HasSubstr("(limit: unit gyro range ±150 deg/s)")));
  }
}

}  // namespace
}  // namespace adahrs::calib

namespace adahrs::calib {
namespace {

TEST(SequenceValidation, EmptyStepsAndEmptyProfileRefusedByTheirRules) {
  const testing::TempFile file("empty.json", R"({
    "format_version": 1, "name": "empty", "description": "", "unit_kind": "imu", "steps": []})");
  const std::vector<SequenceProblem> problems = CheckSequenceFile(file.path(), {});
  ASSERT_THAT(problems, ::testing::SizeIs(1));
  EXPECT_EQ(problems[0].path, "$.steps");
  EXPECT_EQ(problems[0].rule, "a sequence needs at least one step");
  const testing::TempFile profile("empty_profile.json", R"({
    "format_version": 1, "name": "p", "description": "", "unit_kind": "imu",
    "steps": [{"kind": "thermal_profile", "profile_name": "P", "profile_steps": []}]})");
  const std::vector<SequenceProblem> profile_problems = CheckSequenceFile(profile.path(), {});
  ASSERT_THAT(profile_problems, ::testing::SizeIs(1));
  EXPECT_EQ(profile_problems[0].path, "$.steps[0].profile_steps");
  EXPECT_EQ(profile_problems[0].rule, "a profile holds 1…256 steps, got 0");
}

}  // namespace
}  // namespace adahrs::calib
