// A station file's instrument limits reach the sequence validator (calib/sequence/
// station_limits.h): the shipped stations pass every shipped sequence of their bench, a station
// with a narrower instrument refuses them naming the step and that instrument's limit, and the
// ADTS's pressure ranges become altitudes and airspeeds by the ISA formulas worked by hand.
#include "calib/sequence/station_limits.h"
#include "adahrs_build_paths.h"

#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/sequence/execution_plan.h"
#include "calib/sequence/sequence_json.h"
#include "calib/sequence/validation.h"

namespace adahrs::calib {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

const std::string kSource = ADAHRS_SOURCE_DIR;
const std::string kImuStation = kSource + "/docs/examples/station-virtual-rig.json";
const std::string kAdsStation = kSource + "/docs/examples/station-virtual-rig-ads.json";
const std::string kSequences = kSource + "/calib/sequences/";

hil::Station StationWith(const std::string& file, const nlohmann::json& patch) {
  nlohmann::json j = common::ParamReader::LoadFile(file);
  j.merge_patch(patch);
  return hil::Station::FromJson(common::ParamReader(j, file));
}

std::string Refusal(const std::string& sequence_file, const SequenceLimits& limits) {
  try {
    LoadValidSequence(sequence_file, limits);
  } catch (const SequenceError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(StationLimits, NoDeclaredLimitsKeepTheDefaults) {
  nlohmann::json j = common::ParamReader::LoadFile(kImuStation);
  for (auto& [role, entry] : j["instruments"].items()) entry.erase("limits");
  const SequenceLimits limits =
      LimitsForStation(hil::Station::FromJson(common::ParamReader(j, "s.json")));
  const SequenceLimits defaults;
  EXPECT_EQ(limits.table_max_rate_dps, defaults.table_max_rate_dps);
  EXPECT_EQ(limits.table_max_accel_dps2, defaults.table_max_accel_dps2);
  EXPECT_EQ(limits.chamber_min_c, defaults.chamber_min_c);
  EXPECT_EQ(limits.chamber_max_c, defaults.chamber_max_c);
  EXPECT_EQ(limits.chamber_max_ramp_c_per_min, defaults.chamber_max_ramp_c_per_min);
  EXPECT_EQ(limits.adts_alt_max_ft, defaults.adts_alt_max_ft);
}

TEST(StationLimits, DeclaredLimitsReplaceTheInstrumentDefaults) {
  const SequenceLimits imu = LimitsForStation(hil::Station::Load(kImuStation));
  EXPECT_EQ(imu.table_max_rate_dps, 360.0);
  EXPECT_EQ(imu.table_max_accel_dps2, 500.0);
  EXPECT_EQ(imu.chamber_min_c, -70.0);
  EXPECT_EQ(imu.chamber_max_c, 180.0);
  EXPECT_EQ(imu.chamber_max_ramp_c_per_min, 3.5);

  const SequenceLimits ads = LimitsForStation(hil::Station::Load(kAdsStation));
  EXPECT_EQ(ads.ads_chamber_min_c, -50.0);
  EXPECT_EQ(ads.ads_chamber_max_c, 100.0);
  EXPECT_EQ(ads.ads_chamber_max_ramp_c_per_min, 3.5);
  EXPECT_EQ(ads.chamber_max_c, SequenceLimits{}.chamber_max_c);  // the F4's untouched
  // By hand (protocols.md §5): 7,500 Pa lies above the tropopause, h = 11,000 m +
  // (R·T11/g0)·ln(p11/p) = 11,000 + 6,341.6·ln(22,632.06/7,500) = 18,004.1 m = 59,068.5 ft;
  // 135,500 Pa: h = (T0/L)·(1 − (p/p0)^(R·L/g0)) = −2,520.4 m = −8,269.2 ft; Qc 90,000 Pa:
  // Vc = a0·√(5·((qc/p0 + 1)^(2/7) − 1)) = 660.07 kt.
  EXPECT_NEAR(ads.adts_alt_max_ft, 59068.5, 0.5);
  EXPECT_NEAR(ads.adts_alt_min_ft, -8269.2, 0.5);
  EXPECT_NEAR(ads.adts_cas_max_kt, 660.07, 0.01);
  EXPECT_EQ(ads.adts_max_alt_rate_ft_per_min, 100000.0);
  EXPECT_EQ(ads.adts_max_cas_rate_kt_per_min, 2000.0);
}

TEST(StationLimits, ShippedStationsPassEveryShippedSequenceOfTheirBench) {
  const SequenceLimits imu = LimitsForStation(hil::Station::Load(kImuStation));
  const SequenceLimits ads = LimitsForStation(hil::Station::Load(kAdsStation));
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kSequences)) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    const ParsedSequence parsed = ParseSequenceFile(entry.path().string());
    const SequenceLimits& limits = parsed.sequence.unit_kind == UnitKind::kImu ? imu : ads;
    EXPECT_EQ(Refusal(entry.path().string(), limits), "accepted");
    ++checked;
  }
  EXPECT_EQ(checked, 10);
}

TEST(StationLimits, ANarrowChamberRefusesAShippedSequenceNamingStepAndLimit) {
  const hil::Station narrow = StationWith(
      kImuStation,
      {{"instruments", {{"imu_chamber", {{"limits", {{"min_c", -10.0}, {"max_c", 40.0}}}}}}}});
  const std::string burn_in = kSequences + "imu_burn_in.json";
  // imu_burn_in's profile (step 3) ramps first to −40 °C (calib/sequences/imu_burn_in.json).
  EXPECT_THAT(Refusal(burn_in, LimitsForStation(narrow)),
              AllOf(HasSubstr("$.steps[3].profile_steps[0].target_c: temperature -40 degC beyond "
                              "the chamber (Watlow F4)'s range"),
                    HasSubstr("(limit: chamber (Watlow F4) -10…40 degC)")));

  // The ADS bench's chamber limits only its sequences: the IMU one still passes with a narrow 942.
  const hil::Station narrow_942 = StationWith(
      kAdsStation,
      {{"instruments", {{"ads_chamber", {{"limits", {{"min_c", -10.0}, {"max_c", 40.0}}}}}}}});
  EXPECT_EQ(Refusal(burn_in, LimitsForStation(narrow_942)), "accepted");
  EXPECT_THAT(Refusal(kSequences + "ads_burn_in.json", LimitsForStation(narrow_942)),
              HasSubstr("(limit: chamber (Watlow 942) -10…40 degC)"));
}

TEST(StationLimits, ANarrowTableOrAdtsRefusesNamingItsLimit) {
  const hil::Station slow_table = StationWith(
      kImuStation, {{"instruments", {{"rate_table", {{"limits", {{"max_rate_dps", 100.0}}}}}}}});
  EXPECT_THAT(Refusal(kSequences + "imu_sensor_calibration.json", LimitsForStation(slow_table)),
              AllOf(HasSubstr("beyond the rate table's rate limit"),
                    HasSubstr("(limit: rate table ±100 deg/s)")));
  const hil::Station gentle_table = StationWith(
      kImuStation, {{"instruments", {{"rate_table", {{"limits", {{"max_accel_dps2", 10.0}}}}}}}});
  EXPECT_THAT(Refusal(kSequences + "imu_sensor_calibration.json", LimitsForStation(gentle_table)),
              HasSubstr("(limit: rate table acceleration 10 deg/s^2)"));
  // An ADTS that cannot go below 30,000 ft's pressure (30,089 Pa) refuses the 40,000 ft aims.
  const hil::Station low_adts =
      StationWith(kAdsStation,
                  {{"instruments",
                    {{"adts", {{"limits", {{"ps_min_pa", 30089.0}, {"ps_max_pa", 110000.0}}}}}}}});
  EXPECT_THAT(
      Refusal(kSequences + "ads_calibration.json", LimitsForStation(low_adts)),
      AllOf(HasSubstr("outside the air data test set (ADTS)'s range"), HasSubstr(".alt_ft")));
}

TEST(StationLimits, ThePlanMovesTheChamberAtTheStationsDeclaredRates) {
  const hil::Station station = hil::Station::Load(kAdsStation);
  const Sequence burn_in = LoadValidSequence(kSequences + "ads_burn_in.json", {});
  const ExecutionPlan plan =
      ExpandSequence(burn_in, LimitsForStation(station), TimingForStation(station, UnitKind::kAds));
  // By hand from calib/sequences/ads_burn_in.json and the station's 5 / 3.5 degC/min: cooling
  // 25 -> -40, 85 -> -40 twice, 85 -> 25 (65 + 250 + 60 = 375 degC at 3.5: 6,428.57 s),
  // heating -40 -> 85 three times (375 degC at 5: 4,500 s), the 600 s soak at 25 degC, six
  // 1,800 s logs, no operator time (virtual fixture): 22,328.57 s.
  EXPECT_NEAR(plan.duration_estimate_s, 22328.57, 0.01);

  // The run it plans, measured: ads_burn_in on the virtual rig's ADS bench finished in 22,896 s
  // of rig time (the plan at the former fixed 1 degC/min said 56,460 s). The rig's chamber air
  // (docs/rig/watlow-942.md, a first-order loop, tau = 120 s, slope limited to the capacities)
  // leaves its capacity limit tau * rate from the set point and then needs tau * ln(tau * rate /
  // band) to enter the band where the plan's slew spends tau: per heating move into 2 degC
  // 120 * (ln(10 / 2) - 1) = 73.1 s, per cooling move 120 * (ln(7 / 2) - 1) = 30.3 s, the last
  // cooling move into 1 degC 120 * (ln(7 / 1) - 1) = 113.5 s: 3 * 73.1 + 3 * 30.3 + 113.5 =
  // 423.7 s the plan must be short by. The residual control cycling (+-0.3 degC, 90 s period)
  // moves the instant a move enters its band by up to half a period: 7 moves * 45 s = 315 s.
  constexpr double kMeasured_s = 22896.0;
  constexpr double kApproach_s = 3 * 73.1 + 3 * 30.3 + 113.5;
  constexpr double kCycling_s = 7 * 45.0;
  EXPECT_NEAR(kMeasured_s, plan.duration_estimate_s + kApproach_s, kCycling_s);

  // Without declared rates the plan keeps the fixed 1 degC/min.
  nlohmann::json j = common::ParamReader::LoadFile(kAdsStation);
  j["instruments"]["ads_chamber"]["limits"].erase("heat_rate_c_per_min");
  j["instruments"]["ads_chamber"]["limits"].erase("cool_rate_c_per_min");
  const hil::Station undeclared = hil::Station::FromJson(common::ParamReader(j, "s.json"));
  EXPECT_NEAR(
      ExpandSequence(burn_in, {}, TimingForStation(undeclared, UnitKind::kAds)).duration_estimate_s,
      56460.0 - 60.0,  // the figure less the 60 s prompt a fixture skips
      0.01);
  // An IMU batch on that station takes the F4's rates, which it does not declare.
  EXPECT_FALSE(TimingForStation(station, UnitKind::kImu).chamber_heat_c_per_min.has_value());
}

}  // namespace
}  // namespace adahrs::calib
