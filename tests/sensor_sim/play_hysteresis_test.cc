// The play-operator law (sensor_sim/play_hysteresis.h) against the properties a rate-independent
// hysteresis with return-point memory has (saturation, exact minor-loop closure, wiping-out,
// independence of the path between extremes) and against what makes it another family than the
// travel law: a branch that leaves its reversal with a finite slope, and loops whose size depends
// on where they lie.
#include "sensor_sim/play_hysteresis.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sensor_sim/preisach_hysteresis.h"

namespace adahrs::sensor_sim {
namespace {

constexpr double kSpan = 20.0, kLow = 0.0, kHigh = 100.0;

TEST(PlayHysteresis, SaturatesAfterATravelOfOneSpanAtTheRangesCentre) {
  PlayHysteresis h(kSpan, kLow, kHigh);
  EXPECT_EQ(h.Update(40.0), 0.0);
  EXPECT_NEAR(h.Update(50.0), -1.0, 1e-12);  // at the centre the envelope is 1
  EXPECT_NEAR(h.Update(30.0), 1.0 * (1.0 + 0.6 * (30.0 - 50.0) / 50.0), 1e-12);
  EXPECT_LT(h.Update(49.0), 0.0);
}

TEST(PlayHysteresis, MinorLoopsCloseAndAreWipedOut) {
  PlayHysteresis h(kSpan, kLow, kHigh), direct(kSpan, kLow, kHigh);
  for (PlayHysteresis* p : {&h, &direct}) {
    p->Update(50.0);
    p->Update(10.0);
  }
  // A minor loop from the reversal at 32 down to 27 and back returns to the state it left.
  const double at_32 = h.Update(32.0);
  EXPECT_GT(at_32, -0.8);  // not saturated: the closure is not the clamp's
  h.Update(27.0);
  EXPECT_NEAR(h.Update(32.0), at_32, 1e-12);
  // Continuing up, the loop is forgotten: the same state at 45 as without the excursion.
  direct.Update(32.0);
  EXPECT_NEAR(h.Update(45.0), direct.Update(45.0), 1e-12);
}

TEST(PlayHysteresis, DependsOnTheExtremesNotOnThePathBetweenThem) {
  PlayHysteresis coarse(kSpan, kLow, kHigh), fine(kSpan, kLow, kHigh);
  coarse.Update(10.0);
  fine.Update(10.0);
  coarse.Update(90.0);
  coarse.Update(55.0);
  // A rise with noise reversals far smaller than the smallest radius, then a fall.
  for (int i = 1; i <= 800; ++i) fine.Update(10.0 + 0.1 * i + 0.05 * std::sin(i));
  fine.Update(90.0);
  for (int i = 1; i <= 350; ++i) fine.Update(90.0 - 0.1 * i);
  EXPECT_NEAR(fine.state(), coarse.state(), 1e-9);
}

// The travel law leaves a reversal with zero slope (Rayleigh); the play law with a finite one,
// so a tenth of the span moves it several times further.
TEST(PlayHysteresis, LeavesAReversalFasterThanTheTravelLaw) {
  PlayHysteresis play(kSpan, kLow, kHigh);
  PreisachHysteresis travel(kSpan);
  for (double x : {50.0, 100.0, 50.0}) {
    play.Update(x);
    travel.Update(x);
  }
  const double play_move = std::abs(play.Update(52.0) - play.Update(50.0));
  const double travel_move = std::abs(travel.Update(52.0) - travel.Update(50.0));
  EXPECT_GT(play_move, 3.0 * travel_move);
}

// The same excursion makes a larger loop near the top of the range than near the bottom; the
// travel law's would be equal.
TEST(PlayHysteresis, LoopSizeDependsOnWhereTheLoopLies) {
  auto loop_height = [](double centre) {
    PlayHysteresis h(kSpan, kLow, kHigh);
    h.Update(centre);
    h.Update(centre + 0.3 * kSpan);
    const double falling_start = h.Update(centre);
    h.Update(centre - 0.3 * kSpan);
    return std::abs(h.Update(centre) - falling_start);
  };
  EXPECT_GT(loop_height(85.0), 2.0 * loop_height(15.0));
}

TEST(PlayHysteresis, RefusesAnEmptyRangeOrSpan) {
  EXPECT_THROW(PlayHysteresis(0.0, kLow, kHigh), std::invalid_argument);
  EXPECT_THROW(PlayHysteresis(kSpan, kHigh, kLow), std::invalid_argument);
}

}  // namespace
}  // namespace adahrs::sensor_sim
