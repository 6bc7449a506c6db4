#include "sensor_sim/die_thermal.h"

#include <cmath>

#include <gtest/gtest.h>

namespace adahrs::sensor_sim {
namespace {

constexpr double kStep_s = 0.01;

TEST(DieThermal, StepResponseIsFirstOrderWithTau) {
  DieThermalParams p = DieThermalParams::Typical();
  p.effects.self_heating = false;
  DieThermal die(p, kStep_s, 25.0);
  const int steps_per_tau = static_cast<int>(std::lround(p.tau_s / kStep_s));
  for (int i = 0; i < steps_per_tau; ++i) die.Step(35.0);
  // Analytic: 1 − e^−1 = 63.212 % of the 10 °C step after one time constant. The exact
  // discretisation leaves only rounding error.
  EXPECT_NEAR(die.die_temp_c(), 25.0 + 10.0 * (1.0 - std::exp(-1.0)), 1e-9);
}

TEST(DieThermal, RampLagsByTauTimesRate) {
  DieThermalParams p = DieThermalParams::Typical();
  p.effects.self_heating = false;
  DieThermal die(p, kStep_s, 0.0);
  const double rate_c_per_s = 1.0 / 60.0;  // 1 °C/min, a common chamber ramp
  double air_c = 0.0;
  const int steps = static_cast<int>(10 * p.tau_s / kStep_s);
  for (int i = 0; i < steps; ++i) {
    air_c += rate_c_per_s * kStep_s;
    die.Step(air_c);
  }
  // Steady-state lag of a first-order system on a ramp is rate·tau (5 °C at 1 °C/min, tau 5 min;
  // physics.md §6 row 3). The air value is held over each step, adding half a step of lag.
  EXPECT_NEAR(air_c - die.die_temp_c(), rate_c_per_s * (p.tau_s + kStep_s / 2), 1e-3);
}

TEST(DieThermal, SelfHeatingSettlesAboveAir) {
  DieThermal die(DieThermalParams::Typical(), kStep_s, 20.0);
  for (int i = 0; i < static_cast<int>(20 * 300.0 / kStep_s); ++i) die.Step(20.0);
  EXPECT_NEAR(die.die_temp_c(), 23.0, 1e-6);
}

TEST(DieThermal, EffectsOffFollowAirAtOnce) {
  DieThermalParams p = DieThermalParams::Typical();
  p.effects = DieThermalEffects::Nominal();
  DieThermal die(p, kStep_s, 20.0);
  EXPECT_DOUBLE_EQ(die.Step(-40.0), -40.0);
  EXPECT_DOUBLE_EQ(die.Step(85.0), 85.0);
}

TEST(DieThermal, HoldEqualsSteppingThroughTheSameTime) {
  DieThermalParams p = DieThermalParams::Typical();
  DieThermal stepped(p, kStep_s, 25.0);
  DieThermal held(p, kStep_s, 25.0);
  const int steps = 180000;  // 30 min of 10 ms frames
  for (int i = 0; i < steps; ++i) stepped.Step(-40.0);
  held.Hold(-40.0, steps * kStep_s);
  EXPECT_NEAR(held.die_temp_c(), stepped.die_temp_c(), 1e-9);
  const double target_c = -40.0 + p.self_heating_c;
  EXPECT_NEAR(held.die_temp_c(), target_c + (25.0 - target_c) * std::exp(-1800.0 / p.tau_s), 1e-9);
  DieThermal short_hold(p, kStep_s, 25.0);
  short_hold.Hold(-40.0, p.tau_s);  // one time constant: 1/e of the step left
  EXPECT_NEAR(short_hold.die_temp_c(), target_c + (25.0 - target_c) * std::exp(-1.0), 1e-9);
}

TEST(DieThermal, JsonRoundTripAndDrawDeterminism) {
  const DieThermalParams a = DieThermalParams::Draw(7);
  EXPECT_EQ(a, DieThermalParams::Draw(7));
  EXPECT_NE(a, DieThermalParams::Draw(8));
  const nlohmann::json j = a.ToJson();
  EXPECT_EQ(DieThermalParams::FromJson(common::ParamReader(j, "test")), a);
}

TEST(DieThermal, BadParameterNamesPath) {
  nlohmann::json j = DieThermalParams::Typical().ToJson();
  j["tau_s"] = -3.0;
  try {
    DieThermalParams::FromJson(common::ParamReader(j, "unit.json", "$.thermal"));
    FAIL() << "accepted a negative time constant";
  } catch (const common::ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("$.thermal.tau_s"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace adahrs::sensor_sim
