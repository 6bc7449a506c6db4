#include "hil/clock.h"

#include <thread>

#include <gtest/gtest.h>

namespace adahrs::hil {
namespace {

TEST(Clock, ScaledClockRunsAtItsScale) {
  ScaledClock clock(100.0);
  const auto start = std::chrono::steady_clock::now();
  clock.SleepS(20.0);  // 0.2 s of wall time
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(wall_s, 0.2);
  EXPECT_LT(wall_s, 0.2 + 0.2);  // sleep overshoot on a loaded machine
  EXPECT_NEAR(clock.NowS(), 100.0 * wall_s, 100.0 * 0.01);
  EXPECT_EQ(clock.WallTimeout(30.0), std::chrono::milliseconds(300));
  EXPECT_EQ(clock.WallTimeout(0.0), std::chrono::milliseconds(1));
}

TEST(Clock, WallClockIsScaleOne) {
  const auto clock = MakeClock(1.0);
  EXPECT_NE(dynamic_cast<WallClock*>(clock.get()), nullptr);
  EXPECT_EQ(clock->WallTimeout(2.0), std::chrono::milliseconds(2000));
  EXPECT_NE(dynamic_cast<ScaledClock*>(MakeClock(60.0).get()), nullptr);
}

TEST(Clock, RefusesAnUnusableScale) {
  EXPECT_THROW(ScaledClock(0.0), std::invalid_argument);
  EXPECT_THROW(ScaledClock(-5.0), std::invalid_argument);
}

}  // namespace
}  // namespace adahrs::hil
