#include "rig_sim/rate_table.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/random.h"
#include "common/units.h"

namespace adahrs::rig_sim {
namespace {

constexpr double kTick_s = RateTable::kTick_s;

// Runs the table tick by tick until `done` holds; returns the time, or -1 after `limit_s`.
template <typename Done>
double TimeUntil(RateTable& table, double limit_s, Done done) {
  while (table.time_s() < limit_s) {
    table.AdvanceTo(table.time_s() + kTick_s);
    if (done()) return table.time_s();
  }
  return -1.0;
}

TEST(RateTable, ReachesACommandedRateAfterTheRampAndTheLoopTail) {
  const RateTableParams p;  // a = 100 deg/s², tau = 0.05 s, band 0.01 deg/s
  RateTable table(p, 0.0);
  ASSERT_EQ(table.Jog(100.0), RateTableRefusal::kNone);
  // Mid-ramp the platter lags the reference ramp a·t by a·tau·(1 − e^(−t/tau)) (exact solution).
  table.AdvanceTo(0.5);
  const double expected_dps = 100.0 * 0.5 - 100.0 * 0.05 * (1.0 - std::exp(-0.5 / 0.05));
  EXPECT_NEAR(table.measured_rate_dps(), expected_dps, 1e-9);  // closed form, rounding only
  // Inside the band after t = Δr/a + tau·ln(a·tau/ε) = 1 + 0.05·ln(500) = 1.3107 s.
  const double t_s = TimeUntil(table, 5.0, [&] { return table.status().at_rate; });
  const double analytic_s = 100.0 / 100.0 + 0.05 * std::log(100.0 * 0.05 / 0.01);
  EXPECT_NEAR(t_s, analytic_s, 1.5 * kTick_s);  // the check runs once per 1 ms tick
  table.AdvanceTo(3.0);
  EXPECT_NEAR(table.measured_rate_dps(), 100.0, 1e-9);
  EXPECT_TRUE(table.status().moving);
}

TEST(RateTable, AngleIsTheIntegralOfTheRateProfile) {
  RateTableParams p;
  p.rate_ripple_ratio = 0.0;
  RateTable table(p, 10.0);
  ASSERT_EQ(table.Jog(-50.0), RateTableRefusal::kNone);
  table.AdvanceTo(4.0);
  // Ramp 0 → R at a, then R, delayed by the loop: θ = θ0 + R·t − R²/(2a) − R·tau once settled
  // (e^(−3.5/0.05) is negligible).
  const double r = -50.0, a = 100.0, tau = 0.05;
  EXPECT_NEAR(table.unwrapped_angle_deg(),
              10.0 + r * 4.0 - r * std::fabs(r) / (2 * a) - r * tau,
              1e-9);  // −175°: closed-form integration, rounding only
  EXPECT_NEAR(table.measured_angle_deg(), 185.0, 1e-9);
}

TEST(RateTable, PositionMovesEndAtTheTargetTheShortestWayRound) {
  const RateTableParams p;  // move at 60 deg/s, a = 100 deg/s²
  RateTable table(p, 0.0);
  ASSERT_EQ(table.MoveTo(90.0), RateTableRefusal::kNone);
  // Trapezoid: 90/60 + 60/100 = 2.1 s, then the loop settles (a few tau) into the 0.001° band.
  const double t_s = TimeUntil(table, 10.0, [&] { return table.status().in_position; });
  EXPECT_GT(t_s, 2.1);
  EXPECT_LT(t_s, 2.1 + 10 * p.rate_loop_tau_s);
  EXPECT_NEAR(table.measured_angle_deg(), 90.0, p.in_position_band_deg);
  table.AdvanceTo(t_s + 2.0);
  EXPECT_NEAR(table.measured_angle_deg(), 90.0, 1e-9);  // converges exactly (∫(r − y)dt = 0)
  EXPECT_EQ(table.measured_rate_dps(), 0.0);
  // From 90° to −10° (350°) the short way is −100°, through 0, never past 90°.
  ASSERT_EQ(table.MoveTo(-10.0), RateTableRefusal::kNone);
  double most_deg = table.unwrapped_angle_deg();
  while (table.time_s() < t_s + 10.0) {
    table.AdvanceTo(table.time_s() + kTick_s);
    most_deg = std::max(most_deg, table.unwrapped_angle_deg());
  }
  EXPECT_NEAR(table.unwrapped_angle_deg(), -10.0, 1e-9);
  EXPECT_NEAR(table.measured_angle_deg(), 350.0, 1e-9);
  EXPECT_LE(most_deg, 90.0 + 1e-9);
  EXPECT_TRUE(table.status().in_position);
}

TEST(RateTable, AMoveStartedWhileTurningStillEndsAtTheTarget) {
  RateTableParams p;
  p.accel_dps2 = 37.5;
  RateTable table(p, 0.0);
  table.Jog(150.0);
  table.AdvanceTo(2.5);  // still accelerating: 93.75 deg/s, lagging the reference by a·tau
  ASSERT_GT(table.measured_rate_dps(), 90.0);
  // The braking distance 93.75²/(2·37.5) = 117° exceeds the 80° ahead, so it overshoots, turns
  // back and ends on the target; the loop's lag (tau·y = 4.7°) must not be left as an offset.
  table.MoveTo(table.measured_angle_deg() + 80.0);
  const double target_deg = table.unwrapped_angle_deg() + 80.0;
  table.AdvanceTo(20.0);
  EXPECT_NEAR(table.unwrapped_angle_deg(), target_deg, 1e-9);
  EXPECT_TRUE(table.status().in_position);
}

TEST(RateTable, TheTimelineDoesNotDependOnTheCallPattern) {
  const RateTableParams p;
  RateTable frames(p, 0.0), random_steps(p, 0.0);
  common::Rng rng(20240604);
  // Commands at fixed times; one table advanced in 10 ms frames, the other in random steps
  // (0.1…37 ms) that also land on the command times.
  struct Command {
    double t_s;
    int kind;
    double x;
  };
  const Command script[] = {{0.0, 0, 120.0},
                            {1.234, 1, 40.0},
                            {2.5, 0, -80.0},
                            {4.0, 2, 200.0},
                            {7.0, 3, 0.0},
                            {7.5, 2, 33.3}};
  auto apply = [](RateTable& t, const Command& c) {
    if (c.kind == 0) t.Jog(c.x);
    if (c.kind == 1) t.SetAcceleration(c.x);
    if (c.kind == 2) t.MoveTo(c.x);
    if (c.kind == 3) t.StartSine(2.0, 0.5, 1);
  };
  double t_frames = 0.0, t_random = 0.0;
  for (size_t i = 0; i <= std::size(script); ++i) {
    const double until_s = i < std::size(script) ? script[i].t_s : 12.0;
    while (t_frames + 0.01 <= until_s + 1e-12) frames.AdvanceTo(t_frames += 0.01);
    frames.AdvanceTo(until_s);
    while (t_random < until_s) {
      t_random = std::min(until_s, t_random + rng.Uniform(1e-4, 0.037));
      random_steps.AdvanceTo(t_random);
    }
    ASSERT_EQ(frames.time_s(), random_steps.time_s());
    // Bit-identical: both ran the same ticks with the same commands.
    EXPECT_EQ(frames.unwrapped_angle_deg(), random_steps.unwrapped_angle_deg()) << until_s;
    EXPECT_EQ(frames.measured_rate_dps(), random_steps.measured_rate_dps()) << until_s;
    if (i < std::size(script)) {
      apply(frames, script[i]);
      apply(random_steps, script[i]);
    }
  }
}

TEST(RateTable, CommandsBeyondTheLimitsAreRefusedNotClamped) {
  RateTableParams p;
  p.max_rate_dps = 200.0;
  RateTable table(p, 0.0);
  EXPECT_EQ(table.Jog(500.0), RateTableRefusal::kBeyondLimit);
  EXPECT_EQ(table.Jog(-200.5), RateTableRefusal::kBeyondLimit);
  EXPECT_EQ(table.Jog(std::nan("")), RateTableRefusal::kBeyondLimit);
  EXPECT_EQ(table.SetAcceleration(501.0), RateTableRefusal::kBeyondLimit);
  EXPECT_EQ(table.SetAcceleration(0.0), RateTableRefusal::kBeyondLimit);
  // 10° at 10 Hz: peak rate 628 deg/s > 200; 1° at 5 Hz: 31 deg/s but 987 deg/s² > 500.
  EXPECT_EQ(table.StartSine(10.0, 10.0, 1), RateTableRefusal::kBeyondLimit);
  EXPECT_EQ(table.StartSine(1.0, 5.0, 1), RateTableRefusal::kBeyondLimit);
  table.AdvanceTo(2.0);
  EXPECT_EQ(table.commanded_rate_dps(), 0.0);
  EXPECT_EQ(table.measured_rate_dps(), 0.0);
  EXPECT_EQ(table.acceleration_dps2(), 100.0);
  EXPECT_EQ(table.Jog(200.0), RateTableRefusal::kNone);
}

TEST(RateTable, InterlockBrakesAtTheDriveLimitAndRefusesMotionUntilReenabled) {
  const RateTableParams p;  // braking at max_accel 500 deg/s²
  RateTable table(p, 0.0);
  table.Jog(100.0);
  table.AdvanceTo(3.0);
  table.SetInterlockOpen(true);
  EXPECT_FALSE(table.status().servo_on);
  // 100 deg/s at 500 deg/s² is 0.2 s, plus the loop tail from a·tau = 25 deg/s to 0.01 deg/s.
  const double t_s = TimeUntil(table, 10.0, [&] { return !table.status().moving; });
  EXPECT_NEAR(t_s - 3.0, 0.2 + 0.05 * std::log(500.0 * 0.05 / 0.01), 2 * kTick_s);
  EXPECT_EQ(table.Jog(10.0), RateTableRefusal::kInterlockOpen);
  EXPECT_EQ(table.MoveTo(10.0), RateTableRefusal::kInterlockOpen);
  EXPECT_EQ(table.SetServo(true), RateTableRefusal::kInterlockOpen);
  EXPECT_TRUE(table.status().interlock_open);
  table.SetInterlockOpen(false);
  EXPECT_EQ(table.Jog(10.0), RateTableRefusal::kServoOff);  // the servo stays off (INF)
  EXPECT_EQ(table.SetServo(true), RateTableRefusal::kNone);
  EXPECT_EQ(table.Jog(10.0), RateTableRefusal::kNone);
}

TEST(RateTable, ServoOffCoastsDownWithTheFrictionTimeConstant) {
  const RateTableParams p;  // coast_tau_s = 30 s
  RateTable table(p, 0.0);
  table.Jog(100.0);
  table.AdvanceTo(3.0);
  ASSERT_EQ(table.SetServo(false), RateTableRefusal::kNone);
  EXPECT_EQ(table.Jog(10.0), RateTableRefusal::kServoOff);
  table.AdvanceTo(33.0);
  EXPECT_NEAR(table.measured_rate_dps(), 100.0 * std::exp(-1.0), 1e-9);
  // Re-engaging is bumpless: the servo holds the rate the platter has.
  const double rate_dps = table.measured_rate_dps();
  table.SetServo(true);
  table.AdvanceTo(34.0);
  EXPECT_NEAR(table.measured_rate_dps(), rate_dps, 1e-9);
}

TEST(RateTable, RippleIsOncePerRevolutionAndCancelsOverARevolution) {
  RateTableParams p;
  p.rate_ripple_ratio = 1e-4;
  RateTable table(p, 0.0);
  table.Jog(90.0);
  table.AdvanceTo(2.0);
  const double start_deg = table.unwrapped_angle_deg();
  double lo = 1e9, hi = -1e9, sum = 0.0;
  int n = 0;
  while (table.unwrapped_angle_deg() < start_deg + 360.0) {
    table.AdvanceTo(table.time_s() + kTick_s);
    lo = std::min(lo, table.platter_rate_dps());
    hi = std::max(hi, table.platter_rate_dps());
    sum += table.platter_rate_dps();
    ++n;
  }
  // ω = 90·(1 + k·cos θe): extremes 90·(1 ± 1e-4) = ±0.009 deg/s; the mean over one revolution
  // is 90 to within the sampling of the cosine (4000 samples per revolution).
  EXPECT_NEAR(hi, 90.009, 1e-6);
  EXPECT_NEAR(lo, 89.991, 1e-6);
  EXPECT_NEAR(sum / n, 90.0, 1e-5);
  EXPECT_NEAR(table.measured_rate_dps(), 90.0, 1e-9);
}

TEST(RateTable, SineMotionStaysInsideItsEnvelopeAndReturnsToTheStart) {
  RateTableParams p;
  p.rate_ripple_ratio = 0.0;
  RateTable table(p, 30.0);
  ASSERT_EQ(table.StartSine(1.0, 1.0, 2), RateTableRefusal::kNone);
  double lo = 1e9, hi = -1e9, peak_dps = 0.0;
  while (table.time_s() < 2.0) {
    table.AdvanceTo(table.time_s() + kTick_s);
    lo = std::min(lo, table.unwrapped_angle_deg());
    hi = std::max(hi, table.unwrapped_angle_deg());
    peak_dps = std::max(peak_dps, std::fabs(table.measured_rate_dps()));
  }
  // Reference 30 + (1 − cos 2πt): between 30 and 32; peak rate 2π deg/s, attenuated by the loop
  // (gain 1/√(1 + (2π·0.05)²) = 0.954 in steady state).
  EXPECT_GT(lo, 30.0 - 0.05);
  EXPECT_LT(hi, 32.0 + 1e-9);
  EXPECT_GT(hi, 31.9);
  EXPECT_LT(peak_dps, 2 * common::kPi);
  EXPECT_GT(peak_dps, 0.95 * 2 * common::kPi);
  const double t_s = TimeUntil(table, 5.0, [&] { return table.status().in_position; });
  EXPECT_GT(t_s, 2.0);
  EXPECT_NEAR(table.measured_angle_deg(), 30.0, p.in_position_band_deg);
}

TEST(RateTable, AStalledPlatterDoesNotMove) {
  const RateTableParams p;
  RateTable table(p, 0.0);
  table.SetStalled(true);
  table.Jog(50.0);
  table.AdvanceTo(5.0);
  EXPECT_EQ(table.measured_rate_dps(), 0.0);
  EXPECT_EQ(table.platter_rate_dps(), 0.0);
  EXPECT_EQ(table.measured_angle_deg(), 0.0);
  EXPECT_FALSE(table.status().at_rate);
  table.SetStalled(false);
  table.AdvanceTo(8.0);
  EXPECT_TRUE(table.status().at_rate);
}

TEST(RateTable, UnusableParametersAreRefusedByName) {
  RateTableParams p;
  p.accel_dps2 = 600.0;  // above max_accel_dps2
  try {
    RateTable table(p, 0.0);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("accel_dps2 = 600"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace adahrs::rig_sim
