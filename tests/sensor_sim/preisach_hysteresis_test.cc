// The bridges' Preisach law (sensor_sim/preisach_hysteresis.h) against values written out by hand
// from its definition, and against the properties a Preisach model must have whatever its Everett
// function: exact minor-loop closure, wiping-out, congruency of the virgin curve with the
// branches, independence of the step size and of small noise.
#include "sensor_sim/preisach_hysteresis.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/random.h"

namespace adahrs::sensor_sim {
namespace {

double Smoothstep(double t) { return t >= 1.0 ? 1.0 : t * t * (3.0 - 2.0 * t); }

TEST(PreisachHysteresis, VirginCurveThenMajorBranches) {
  PreisachHysteresis h(10.0);
  EXPECT_EQ(h.Update(0.0), 0.0);
  // The virgin curve counts the travel double: 2.5 up is t = 0.5, F = 0.5.
  EXPECT_DOUBLE_EQ(h.Update(2.5), -0.5);
  EXPECT_DOUBLE_EQ(h.Update(5.0), -1.0);
  EXPECT_DOUBLE_EQ(h.Update(50.0), -1.0);
  // Reversal at 50 on -1: after 2.5 down (t = 0.25), F = 0.15625: -1 + 2 F.
  EXPECT_DOUBLE_EQ(h.Update(47.5), -1.0 + 2.0 * 0.15625);
  EXPECT_DOUBLE_EQ(h.Update(40.0), 1.0);
  // Below the origin's mirror of 50 the virgin history is wiped; the state stays saturated.
  EXPECT_DOUBLE_EQ(h.Update(-60.0), 1.0);
}

TEST(PreisachHysteresis, IndependentOfStepSize) {
  PreisachHysteresis coarse(10.0), fine(10.0);
  coarse.Update(0.0);
  fine.Update(0.0);
  coarse.Update(20.0);
  coarse.Update(13.0);
  for (int i = 1; i <= 1000; ++i) fine.Update(20.0 * i / 1000.0);
  for (int i = 1; i <= 1000; ++i) fine.Update(20.0 - 7.0 * i / 1000.0);
  EXPECT_NEAR(fine.state(), coarse.state(), 1e-12);
  // From -1 at 20, down 7 (t = 0.7): F(0.7) = 0.784.
  EXPECT_DOUBLE_EQ(coarse.state(), -1.0 + 2.0 * 0.784);
}

// A minor loop closes exactly: back at its start the state is what it was there, for a loop of
// any size, so crossing the start is continuous and the state then continues the older branch.
TEST(PreisachHysteresis, MinorLoopsCloseExactlyAndAreWipedOut) {
  PreisachHysteresis h(10.0);
  h.Update(-30.0);
  h.Update(30.0);                     // saturated -1
  const double at_3 = h.Update(3.0);  // falling from 30: t = 2.7 -> +1
  EXPECT_DOUBLE_EQ(at_3, 1.0);
  h.Update(-2.0);  // falling further (same branch)
  const double at_m2 = h.state();
  h.Update(4.0);  // minor loop up: -2 -> 4 (t = 0.6, F = 0.648)
  EXPECT_DOUBLE_EQ(h.state(), at_m2 - 2.0 * 0.648);
  h.Update(1.0);  // and back down 3 (t = 0.3, F = 0.216)
  EXPECT_DOUBLE_EQ(h.state(), at_m2 - 2.0 * 0.648 + 2.0 * 0.216);
  EXPECT_DOUBLE_EQ(h.Update(4.0), at_m2 - 2.0 * 0.648);  // inner loop closes exactly
  EXPECT_NEAR(h.Update(-2.0 + 1e-9), at_m2, 1e-8);
  EXPECT_NEAR(h.Update(-2.0), at_m2, 1e-15);  // outer loop closes exactly
  // Beyond -2 the -2 -> 4 loop is forgotten: the branch from 30 continues.
  PreisachHysteresis clean(10.0);
  clean.Update(-30.0);
  clean.Update(30.0);
  EXPECT_DOUBLE_EQ(h.Update(-5.0), clean.Update(-5.0));
}

// The virgin curve meets a branch from an extreme at the extreme's mirror about the origin, and
// the state is continuous there: rise 0 -> 3, fall to -3 (the mirror) and beyond.
TEST(PreisachHysteresis, VirginCurveIsRejoinedContinuouslyAtTheMirrorPoint) {
  PreisachHysteresis h(10.0);
  h.Update(0.0);
  const double at_top = h.Update(3.0);
  EXPECT_DOUBLE_EQ(at_top, -Smoothstep(0.6));
  // Down from 3 to -3: t = 0.6 on the branch, -F(0.6) + 2 F(0.6) = +F(0.6): the virgin value.
  EXPECT_NEAR(h.Update(-3.0), Smoothstep(0.6), 1e-15);
  EXPECT_DOUBLE_EQ(h.Update(-4.0), Smoothstep(0.8));
}

// The pitot at rest: a climb to 450 kt's impact pressure and back to zero, then noise that dips
// below every earlier minimum, keeps the state on the falling major branch (+1): nothing of the
// virgin state survives a full excursion.
TEST(PreisachHysteresis, FullExcursionForgetsTheVirginState) {
  PreisachHysteresis h(6895.0);
  h.Update(0.0);
  h.Update(33000.0);
  EXPECT_DOUBLE_EQ(h.Update(0.0), 1.0);
  common::Rng rng(3);
  // Inside the noise a loop of travel a leaves the branch by at most 2 F(a / span) ~ 6 (a/span)^2.
  for (int i = 0; i < 10000; ++i) {
    EXPECT_GE(h.Update(rng.Uniform(-20.0, 20.0)), 1.0 - 6.0 * std::pow(40.0 / 6895.0, 2));
  }
  EXPECT_DOUBLE_EQ(h.Update(-30.0), 1.0);  // below every noise minimum: the major branch again
}

// A slow ramp with noise (a reversal every few steps) develops the state as the clean ramp does,
// within the law's slope times the noise (max |ds/dx| = 3/span, here 0.3 per unit x 0.05).
TEST(PreisachHysteresis, NoisyRampDevelopsLikeACleanOne) {
  PreisachHysteresis noisy(10.0), clean(10.0);
  noisy.Update(0.0);
  clean.Update(0.0);
  common::Rng rng(12345);
  double worst = 0.0;
  for (int i = 1; i <= 700; ++i) {
    const double x = 0.01 * i;
    worst = std::max(worst, std::abs(noisy.Update(x + rng.Uniform(-0.05, 0.05)) - clean.Update(x)));
  }
  EXPECT_LT(worst, 0.3 * 0.05 + 1e-12);
  EXPECT_NEAR(noisy.state(), -1.0, 1e-3);
}

// Bounded and continuous under random histories of every size: no step of the input moves the
// state by more than the steepest slope (virgin curve: 6/span) times the step.
TEST(PreisachHysteresis, BoundedAndLipschitzOverRandomHistories) {
  common::Rng rng(77);
  double worst_slope = 0.0;
  for (int history = 0; history < 200; ++history) {
    PreisachHysteresis h(10.0);
    double x = rng.Uniform(-20.0, 20.0);
    h.Update(x);
    for (int excursion = 0; excursion < 50; ++excursion) {
      const double aim = rng.Uniform(-25.0, 25.0);
      const int steps = 1 + static_cast<int>(rng.Uniform(0.0, 40.0));
      const double from = x;
      for (int i = 1; i <= steps; ++i) {
        const double next = from + (aim - from) * i / steps;
        const double before = h.state();
        const double after = h.Update(next);
        ASSERT_LE(std::abs(after), 1.0);
        if (next != x)
          worst_slope = std::max(worst_slope, std::abs(after - before) / std::abs(next - x));
        x = next;
      }
    }
  }
  EXPECT_LE(worst_slope, 0.6 + 1e-9);
}

}  // namespace
}  // namespace adahrs::sensor_sim
