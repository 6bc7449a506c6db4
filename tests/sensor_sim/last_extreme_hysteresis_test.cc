#include "sensor_sim/last_extreme_hysteresis.h"

#include <gtest/gtest.h>

namespace adahrs::sensor_sim {
namespace {

TEST(LastExtremeHysteresis, StartsNeutralAndSaturatesAfterOneSpan) {
  LastExtremeHysteresis h(10.0);
  EXPECT_EQ(h.Update(0.0), 0.0);
  // Rising by half a span from state 0: smoothstep(0.5) = 0.5 of the way to −1.
  EXPECT_DOUBLE_EQ(h.Update(5.0), -0.5);
  EXPECT_DOUBLE_EQ(h.Update(10.0), -1.0);
  EXPECT_DOUBLE_EQ(h.Update(50.0), -1.0);
  // Reversal at 50 from −1: after 2.5 of travel down (t = 0.25), smoothstep = 0.15625 of the
  // way from −1 to +1.
  EXPECT_DOUBLE_EQ(h.Update(47.5), -1.0 + 2.0 * 0.15625);
  EXPECT_DOUBLE_EQ(h.Update(40.0), 1.0);
}

TEST(LastExtremeHysteresis, IndependentOfStepSize) {
  // Same path in one step or in a thousand: the state depends only on the extremes.
  LastExtremeHysteresis coarse(10.0);
  LastExtremeHysteresis fine(10.0);
  coarse.Update(0.0);
  fine.Update(0.0);
  coarse.Update(20.0);
  coarse.Update(13.0);
  for (int i = 1; i <= 1000; ++i) fine.Update(20.0 * i / 1000.0);
  for (int i = 1; i <= 1000; ++i) fine.Update(20.0 - 7.0 * i / 1000.0);
  EXPECT_NEAR(fine.state(), coarse.state(), 1e-12);
  // From −1 at 20, down 7 (t = 0.7): smoothstep(0.7) = 0.784.
  EXPECT_DOUBLE_EQ(coarse.state(), -1.0 + 2.0 * 0.784);
}

TEST(LastExtremeHysteresis, ContinuousAtReversalAndNoDriftUnderDither) {
  LastExtremeHysteresis h(10.0);
  h.Update(0.0);
  const double at_top = h.Update(4.0);
  // A reversal by a tiny step changes the state by far less than the step (zero slope).
  EXPECT_NEAR(h.Update(4.0 - 1e-6), at_top, 1e-10);
  // Dither +-0.001 about 4 for 1000 cycles: every excursion that returns past its start closes
  // its minor loop, and the state is back on the branch from 0 each time.
  for (int i = 0; i < 2000; ++i) h.Update(i % 2 ? 4.001 : 3.999);
  EXPECT_NEAR(h.state(), -(0.4001 * 0.4001 * (3.0 - 2.0 * 0.4001)), 1e-12);
}

// Return-point memory: a minor loop inside a branch is forgotten once the input passes its start.
// Rise 0 -> 6, fall to 5, rise to 8: beyond 6 the state is the 0 -> 8 branch's, exactly.
TEST(LastExtremeHysteresis, MinorLoopIsWipedOutBeyondItsStart) {
  LastExtremeHysteresis h(10.0);
  h.Update(0.0);
  h.Update(6.0);
  const double in_loop = h.Update(5.0);
  EXPECT_GT(in_loop, h.Update(6.0) - 1.0);  // inside the loop: its own branch
  EXPECT_DOUBLE_EQ(h.Update(8.0), -(0.8 * 0.8 * (3.0 - 2.0 * 0.8)));
}

// A slow ramp with noise (a reversal every few steps) develops the state as the clean ramp does:
// 0 -> 10 in steps of 0.01 with +-0.05 of noise ends within the noise's travel of -1 (without the
// return-point memory every reversal restarted the smoothstep at zero slope and the same ramp
// ended near -0.2).
TEST(LastExtremeHysteresis, NoisyRampDevelopsLikeACleanOne) {
  LastExtremeHysteresis noisy(10.0), clean(10.0);
  noisy.Update(0.0);
  clean.Update(0.0);
  unsigned seed = 12345;
  for (int i = 1; i <= 700; ++i) {
    seed = seed * 1103515245u + 12345u;
    const double noise = 0.05 * (static_cast<double>((seed >> 16) & 0x7FFF) / 16383.5 - 1.0);
    noisy.Update(0.01 * i + noise);
    clean.Update(0.01 * i);
  }
  EXPECT_NEAR(noisy.state(), clean.state(), 0.02);
}

}  // namespace
}  // namespace adahrs::sensor_sim
