// The target's Preisach operator (firmware_model/target/preisach_q15.h) against the law
// the simulator gives the bridges (sensor_sim/preisach_hysteresis.h, double precision): the
// same input histories, the fixed-point state within its quantisation of the exact one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "common/random.h"
#include "firmware_model/unit_firmware.h"
#include "sensor_sim/preisach_hysteresis.h"

namespace adahrs::firmware_model {
namespace {

constexpr double kQ15 = 1.0 / 32768.0;

CoeffQ31 InverseSpan(double inv) {
  int e = 0;
  std::frexp(inv, &e);
  return CoeffQ31{static_cast<int32_t>(std::lround(std::ldexp(inv, 31 - e))),
                  static_cast<int8_t>(e)};
}

int32_t PressureMantissa(double pa) {
  return static_cast<int32_t>(std::lround(std::ldexp(pa, 31 - kPressureExponent)));
}
double PressureOf(int32_t mantissa) { return std::ldexp(mantissa, kPressureExponent - 31); }

// A fresh pressure operator and the law, fed the same frames (the law sees the Q31 input the
// operator sees): each Step returns the operator's state and keeps the worst |state - law| and
// the cycles of the costliest frame and of all frames whose input moved.
struct OperatorBesideLaw {
  explicit OperatorBesideLaw(double span_pa) : inv_span(InverseSpan(1.0 / span_pa)), law(span_pa) {
    PreisachResetQ15(&op);
  }

  int16_t Step(double p_pa) {
    const int32_t input = PressureMantissa(p_pa);
    const bool moved = op.started != 0 && input != op.last_input;
    DspEngine engine;
    const int16_t state = PreisachUpdateQ15(&engine, &op, input, kPressureExponent, inv_span);
    worst = std::max(worst, std::abs(state * kQ15 - law.Update(PressureOf(input))));
    max_cycles = std::max(max_cycles, engine.cycles());
    if (moved) {
      moving_cycles += engine.cycles();
      ++moving_frames;
    }
    return state;
  }

  CoeffQ31 inv_span;
  PreisachQ15 op;
  sensor_sim::PreisachHysteresis law;
  double worst = 0.0;
  uint32_t max_cycles = 0;
  uint64_t moving_cycles = 0, moving_frames = 0;
};

// Pressure (Pa, the surface's result at 2^17) over a random history of excursions of every size
// (from a few Pa to the whole envelope), stepped in frames of up to 400 Pa: the operator's state
// matches the law to within 5e-4 throughout (Q15 travel, weight and state roundings: a few 3e-5,
// carried through reversals by convex combinations, so they do not grow).
TEST(PreisachQ15, FollowsTheSimulatorsLawOverRandomPressureHistories) {
  constexpr double kSpanPa = 20684.0;  // 20 % FS of a 15 psi bridge
  common::Rng rng(5150);
  double worst = 0.0;
  uint32_t max_cycles = 0;
  uint64_t moving_cycles = 0, moving_frames = 0;
  for (int history = 0; history < 20; ++history) {
    OperatorBesideLaw pair(kSpanPa);
    double p_pa = rng.Uniform(11000.0, 105000.0);
    for (int excursion = 0; excursion < 60; ++excursion) {
      const double size = std::pow(10.0, rng.Uniform(0.5, 5.0));
      const double aim =
          std::clamp(p_pa + (rng.Uniform(0.0, 1.0) < 0.5 ? -size : size), 11000.0, 108000.0);
      while (p_pa != aim) {
        p_pa = aim > p_pa ? std::min(aim, p_pa + rng.Uniform(1.0, 400.0))
                          : std::max(aim, p_pa - rng.Uniform(1.0, 400.0));
        pair.Step(p_pa);
      }
    }
    worst = std::max(worst, pair.worst);
    max_cycles = std::max(max_cycles, pair.max_cycles);
    moving_cycles += pair.moving_cycles;
    moving_frames += pair.moving_frames;
  }
  std::printf(
      "pressure operator: worst |state - law| %.2e over 1,200 excursions, %.1f cycles per "
      "moving frame on average, max %u cycles\n",
      worst,
      static_cast<double>(moving_cycles) / static_cast<double>(moving_frames),
      max_cycles);
  EXPECT_LT(worst, 5e-4);
  EXPECT_LE(max_cycles, 100u);
}

// A thermal operator on a bridge-voltage code that FALLS as the die warms (negative inv_span):
// the state keeps the physical convention, -1 after heating, as the law on temperature gives.
TEST(PreisachQ15, NegativeInverseSpanKeepsTheTemperatureConvention) {
  constexpr double kCodePerDegC = -17448.0;
  constexpr double kSpanC = 20.0;
  const CoeffQ31 inv_span = InverseSpan(1.0 / (kSpanC * kCodePerDegC));
  ASSERT_LT(inv_span.mantissa_q31, 0);
  PreisachQ15 op;
  PreisachResetQ15(&op);
  sensor_sim::PreisachHysteresis law(kSpanC);
  double worst = 0.0;
  double temp_c = 25.0;
  for (const double aim_c : {25.0, 85.0, -40.0, 10.0, 20.0, 12.0, 85.0, 60.0, 70.0}) {
    while (temp_c != aim_c) {
      temp_c = aim_c > temp_c ? std::min(aim_c, temp_c + 0.5) : std::max(aim_c, temp_c - 0.5);
      const int32_t code =
          static_cast<int32_t>(std::lround(6710886.0 + kCodePerDegC * (temp_c - 25.0)));
      DspEngine engine;
      const int16_t state = PreisachUpdateQ15(&engine, &op, code, 31, inv_span);
      worst = std::max(worst, std::abs(state * kQ15 - law.Update(temp_c)));
    }
  }
  EXPECT_LT(worst, 5e-4);
  EXPECT_GT(op.state_q15, 0);  // last move: cooling from 85 to 60, then 10 degC of heating
}

// Input noise reverses the operator every frame; each excursion that returns past its start is
// wiped out, so 200,000 frames of +-4 Pa noise after a climb leave the state within 2 LSB of -1,
// with the law.
TEST(PreisachQ15, NoiseReversalsDoNotWearTheStateDown) {
  OperatorBesideLaw pair(20684.0);
  common::Rng rng(99);
  for (double p = 30000.0; p <= 80000.0; p += 250.0) pair.Step(p);
  const int16_t after_climb = pair.op.state_q15;
  EXPECT_LE(after_climb, -32767);
  for (int i = 0; i < 200000; ++i) pair.Step(80000.0 + rng.Uniform(-4.0, 4.0));
  EXPECT_LE(pair.op.state_q15, after_climb + 2);
  EXPECT_LT(std::abs(pair.op.state_q15 * kQ15 - pair.law.state()), 1e-4);
  EXPECT_LE(pair.op.depth, kPreisachDepth);
}

// A slow sweep with the ADC's noise, as the unit sees its pressure during a test-set ramp
// (60 Pa/s at 100 Hz: 0.6 Pa per frame, +-10 Pa of noise): reversals every few frames, yet the
// state develops as along the clean sweep and as the law does on the same noisy input (within the
// operator's quantisation), and the branch stack stays shallow.
TEST(PreisachQ15, NoisySweepDevelopsLikeTheCleanSweep) {
  constexpr double kSpanPa = 20684.0;
  OperatorBesideLaw pair(kSpanPa);
  sensor_sim::PreisachHysteresis clean(kSpanPa);
  common::Rng rng(7);
  uint8_t deepest = 0;
  int reversals = 0, last_direction = 0;
  double previous = 100000.0;
  clean.Update(100000.0);
  for (int i = 0; i <= 30000; ++i) {
    const double p_pa = 100000.0 - 0.6 * i;  // falling: the state develops towards +1
    const double noisy_pa = PressureOf(PressureMantissa(p_pa + rng.Uniform(-10.0, 10.0)));
    const int16_t state = pair.Step(noisy_pa);
    deepest = std::max(deepest, pair.op.depth);
    const int direction = noisy_pa > previous ? 1 : -1;
    reversals += direction != last_direction ? 1 : 0;
    last_direction = direction;
    previous = noisy_pa;
    if (i % 1000 == 0) {
      EXPECT_NEAR(state * kQ15, clean.Update(p_pa), 0.01) << "at " << p_pa << " Pa";
    }
  }
  std::printf(
      "noisy sweep: %d reversals, worst |state - law| %.2e, deepest stack %u, max %u "
      "cycles\n",
      reversals,
      pair.worst,
      deepest,
      pair.max_cycles);
  EXPECT_GT(reversals, 5000);
  EXPECT_LT(pair.worst, 5e-4);
  EXPECT_LE(deepest, kPreisachDepth);
}

// Power-on in the virgin state, then a pitot's day: 0 -> 450 kt's impact pressure -> 0, then
// noise about zero that dips below every earlier minimum. The state stays on the falling major
// branch (+1 within the noise loops' 6 (a/span)^2 and the operator's 5e-4 of the law), with the
// law, and never returns to the fresh 0.
TEST(PreisachQ15, FullExcursionForgetsThePowerOnState) {
  constexpr double kSpanPa = 6895.0;  // 20 % FS of a 5 psid bridge
  OperatorBesideLaw pair(kSpanPa);
  common::Rng rng(11);
  EXPECT_EQ(pair.Step(0.0), 0);
  for (double qc = 0.0; qc <= 33000.0; qc += 300.0) pair.Step(qc);
  EXPECT_LE(pair.op.state_q15, -32767);
  for (double qc = 33000.0; qc >= 0.0; qc -= 300.0) pair.Step(qc);
  EXPECT_GE(pair.op.state_q15, 32767);
  int16_t lowest = INT16_MAX;
  for (int i = 0; i < 20000; ++i) lowest = std::min(lowest, pair.Step(rng.Uniform(-20.0, 20.0)));
  EXPECT_GE(lowest * kQ15, 1.0 - 6.0 * std::pow(40.0 / kSpanPa, 2) - 5e-4);
  EXPECT_GE(pair.Step(-30.0), 32766);  // below every noise minimum: the major branch again
  EXPECT_LT(pair.worst, 5e-4);
}

// A zero inv_span (the term off) holds the state; the first frame only starts the operator.
TEST(PreisachQ15, ZeroInverseSpanHoldsTheStateAndTheFirstFrameStartsIt) {
  PreisachQ15 op;
  PreisachResetQ15(&op);
  DspEngine engine;
  EXPECT_EQ(PreisachUpdateQ15(&engine, &op, 1000, 31, CoeffQ31{0, 0}), 0);
  EXPECT_EQ(op.started, 1);
  for (int32_t code = 1000; code < 2000000; code += 50000) {
    EXPECT_EQ(PreisachUpdateQ15(&engine, &op, code, 31, CoeffQ31{0, 0}), 0);
  }
  EXPECT_EQ(op.direction, 1);
}

}  // namespace
}  // namespace adahrs::firmware_model
