// Every shipped reference sequence (calib/sequences/*.json) loads and validates against the
// reference hardware's limits, and holds what reference-method.md says it must.
#include <algorithm>
#include <filesystem>
#include <set>
#include "adahrs_build_paths.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/sequence/execution_plan.h"
#include "calib/sequence/validation.h"

namespace adahrs::calib {
namespace {

using ::testing::ElementsAre;

const std::string kDir = std::string(ADAHRS_SOURCE_DIR) + "/calib/sequences/";

Sequence Load(const std::string& name) { return LoadValidSequence(kDir + name + ".json", {}); }

TEST(ShippedSequences, EveryFileLoadsValidatesAndExpands) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(kDir)) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    const Sequence s = LoadValidSequence(entry.path().string(), {});
    EXPECT_EQ(s.name + ".json", entry.path().filename().string());
    const ExecutionPlan plan = ExpandSequence(s, {});
    EXPECT_GT(plan.duration_estimate_s, 0.0);
    names.insert(s.name);
  }
  EXPECT_EQ(names,
            (std::set<std::string>{"ads_acceptance",
                                   "ads_burn_in",
                                   "ads_calibration",
                                   "imu_acceptance",
                                   "imu_burn_in",
                                   "imu_cross_axis_calibration",
                                   "imu_sensor_calibration",
                                   "imu_thermal_calibration_full",
                                   "imu_thermal_sensor_calibration",
                                   "imu_thermal_calibration_trial"}));
}

TEST(ShippedSequences, SensorCalibrationHasSixOrientationsSevenRatesPerAxisAndCrossAxis) {
  const Sequence s = Load("imu_sensor_calibration");
  std::vector<int> accel_orientations;
  std::vector<int> gyro_orientations;
  int cross_axis_steps = 0;
  for (const Step& step : s.steps) {
    if (const auto* a = std::get_if<AccelStep>(&step.body))
      accel_orientations.push_back(a->orientation);
    if (const auto* g = std::get_if<GyroStep>(&step.body)) {
      gyro_orientations.push_back(g->orientation);
      EXPECT_THAT(GyroRates_dps(*g), ElementsAre(-150.0, -100.0, -50.0, 0.0, 50.0, 100.0, 150.0));
    }
    if (const auto* c = std::get_if<CrossAxisStep>(&step.body)) {
      ++cross_axis_steps;
      EXPECT_EQ(c->rate_dps, 150.0);  // thesis Eq. 29: CG = J⁻¹·diag(150)
    }
  }
  EXPECT_THAT(accel_orientations, ElementsAre(11, 12, 21, 22, 31, 32));
  EXPECT_THAT(gyro_orientations, ElementsAre(11, 21, 31));
  EXPECT_EQ(cross_axis_steps, 1);
}

// The staged process's last stage: the sensor calibration's cross-axis step alone, at 25 degC.
TEST(ShippedSequences, CrossAxisCalibrationIsTheSensorRunsCrossAxisStepAt25C) {
  const Sequence s = Load("imu_cross_axis_calibration");
  std::vector<double> targets_c;
  int cross_axis_steps = 0;
  for (const Step& step : s.steps) {
    if (const auto* t = std::get_if<TargetTemperatureStep>(&step.body))
      targets_c.push_back(t->target_c);
    if (const auto* c = std::get_if<CrossAxisStep>(&step.body)) {
      ++cross_axis_steps;
      EXPECT_EQ(c->rate_dps, 150.0);
      EXPECT_EQ(c->packets, 1000);
    }
    EXPECT_FALSE(std::holds_alternative<AccelStep>(step.body));
    EXPECT_FALSE(std::holds_alternative<GyroStep>(step.body));
  }
  EXPECT_THAT(targets_c, ElementsAre(25.0));
  EXPECT_EQ(cross_axis_steps, 1);
}

// The extreme set points a sequence's chamber reaches (target steps and profile ramps).
std::pair<double, double> TemperatureSpanC(const Sequence& s) {
  double lo_c = 1e9;
  double hi_c = -1e9;
  auto see = [&](double c) {
    lo_c = std::min(lo_c, c);
    hi_c = std::max(hi_c, c);
  };
  for (const Step& step : s.steps) {
    if (const auto* t = std::get_if<TargetTemperatureStep>(&step.body)) see(t->target_c);
    if (const auto* p = std::get_if<ThermalProfileStep>(&step.body)) {
      for (const F4ProfileStep& f : p->steps) {
        if (const auto* r = std::get_if<F4RampRate>(&f)) see(r->target_c);
        if (const auto* r = std::get_if<F4RampTime>(&f)) see(r->target_c);
      }
    }
  }
  return {lo_c, hi_c};
}

TEST(ShippedSequences, ThermalSequencesCoverTheirRanges) {
  EXPECT_EQ(TemperatureSpanC(Load("imu_thermal_calibration_trial")),
            std::make_pair(-20.0, 65.0));  // thesis Fig. 17
  EXPECT_EQ(TemperatureSpanC(Load("imu_thermal_calibration_full")), std::make_pair(-40.0, 85.0));
  EXPECT_EQ(TemperatureSpanC(Load("imu_thermal_sensor_calibration")), std::make_pair(-40.0, 85.0));
  EXPECT_EQ(TemperatureSpanC(Load("imu_burn_in")), std::make_pair(-40.0, 85.0));
  EXPECT_EQ(TemperatureSpanC(Load("ads_burn_in")), std::make_pair(-40.0, 85.0));
  EXPECT_EQ(TemperatureSpanC(Load("ads_calibration")), std::make_pair(-40.0, 85.0));
}

TEST(ShippedSequences, AdsBurnInRunsOnTheWatlow942sSetPointsWithLoggedDwells) {
  // The ADS bench's 942 driver runs set points only: three cycles of a set point at each end of
  // the rating and a 30 min logged dwell there.
  const Sequence s = Load("ads_burn_in");
  std::vector<double> dwell_ends_c;
  for (size_t i = 0; i + 1 < s.steps.size(); ++i) {
    EXPECT_FALSE(std::holds_alternative<ThermalProfileStep>(s.steps[i].body));
    const auto* target = std::get_if<TargetTemperatureStep>(&s.steps[i].body);
    const auto* log = std::get_if<LogStep>(&s.steps[i + 1].body);
    if (target == nullptr || log == nullptr) continue;
    EXPECT_EQ(log->duration_s, std::optional<double>(1800.0));
    dwell_ends_c.push_back(target->target_c);
  }
  EXPECT_THAT(dwell_ends_c, ElementsAre(-40.0, 85.0, -40.0, 85.0, -40.0, 85.0));
}

TEST(ShippedSequences, AdsCalibrationPointsDenserWhereToleranceIsTighter) {
  // Largest gap between logged altitudes below and above 10,000 ft (±15 ft below, ±20…80 ft
  // above, reference-method.md Tables 1–5), and between logged airspeeds below and above 100 kt.
  const Sequence s = Load("ads_calibration");
  std::set<double> alts_ft;
  std::set<double> speeds_kt;
  for (size_t i = 0; i + 1 < s.steps.size(); ++i) {
    if (!std::holds_alternative<LogStep>(s.steps[i + 1].body)) continue;
    if (const auto* a = std::get_if<AltitudeStep>(&s.steps[i].body)) alts_ft.insert(a->alt_ft);
    if (const auto* v = std::get_if<AirspeedStep>(&s.steps[i].body)) speeds_kt.insert(v->cas_kt);
  }
  auto max_gap = [](const std::set<double>& points, double from, double to) {
    double gap = 0.0;
    double previous = *points.begin();
    for (double p : points) {
      if (p > from && p <= to) gap = std::max(gap, p - previous);
      previous = p;
    }
    return gap;
  };
  EXPECT_EQ(*alts_ft.begin(), -1000.0);
  EXPECT_EQ(*alts_ft.rbegin(), 50000.0);
  EXPECT_LE(max_gap(alts_ft, -1000.0, 10000.0), 2500.0);
  EXPECT_GE(max_gap(alts_ft, 10000.0, 50000.0), 10000.0);
  EXPECT_EQ(*speeds_kt.rbegin(), 450.0);
  EXPECT_LE(max_gap(speeds_kt, 0.0, 100.0), 20.0);
  EXPECT_GE(max_gap(speeds_kt, 100.0, 450.0), 100.0);
}

}  // namespace
}  // namespace adahrs::calib
