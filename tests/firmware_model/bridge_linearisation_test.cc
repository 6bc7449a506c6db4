// The target's linearisation of a bridge-voltage code (firmware_model/target/
// bridge_linearisation.h) against the closed form origin + (2/kappa)(sqrt(1 + kappa (y - origin))
// - 1), computed here in long double (not the rationalised form the target and the double
// reference use), over a 24-bit code box, for curvatures from the smallest to |k| near 2; and its
// block words.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>

#include "firmware_model/unit_firmware.h"

namespace adahrs::firmware_model {
namespace {

long double ClosedForm(long double origin, long double kappa, long double y) {
  return origin + (2.0L / kappa) * (std::sqrt(1.0L + kappa * (y - origin)) - 1.0L);
}

struct Sweep {
  double worst_codes = 0.0;
  uint32_t max_cycles = 0;
  uint16_t flags = 0;
};

// Every 1,001st code of [origin - half, origin + half] through the target.
Sweep SweepBox(const BridgeLinearisationQ& q, double half) {
  Sweep out;
  const long double kappa =
      std::ldexp(static_cast<long double>(q.curvature_q13), -13 - q.raw_norm.shift);
  for (double y = q.raw_norm.centre - half; y <= q.raw_norm.centre + half; y += 1001.0) {
    DspEngine engine;
    uint16_t flags = 0;
    const int32_t s = LinearisedBridgeCode(&engine, q, static_cast<int32_t>(y), &flags);
    out.flags |= flags;
    out.max_cycles = std::max(out.max_cycles, engine.cycles());
    const long double exact = ClosedForm(q.raw_norm.centre, kappa, static_cast<int32_t>(y));
    out.worst_codes = std::max(out.worst_codes, static_cast<double>(std::fabs(s - exact)));
  }
  return out;
}

// A model-1230 static bridge through the ADS's divider: origin 6.7 M codes, the box +-1.2 M codes
// (-40...+85 degC), half-width 2^21; k from 1/2^13 (the smallest non-zero) up to +-1.5 (a radicand
// down to 0.13 at one end of the box), and +-3 over a box of +-0.3 of the half-width (0.1).
TEST(BridgeLinearisation, FollowsTheClosedFormWithinFourQuotientSteps) {
  const InputNormQ31 raw{6710886, 21};
  const double step_codes = std::ldexp(1.0, raw.shift - 14);  // 128 codes
  for (const auto& [k_q13, half] : {std::pair{int16_t{1}, 1.2e6},
                                    std::pair{int16_t{-1}, 1.2e6},
                                    std::pair{int16_t{2048}, 1.2e6},
                                    std::pair{int16_t{-2048}, 1.2e6},
                                    std::pair{int16_t{8192}, 1.2e6},
                                    std::pair{int16_t{-8192}, 1.2e6},
                                    std::pair{int16_t{12500}, 1.2e6},
                                    std::pair{int16_t{-12500}, 1.2e6},
                                    std::pair{int16_t{24576}, 0.63e6},
                                    std::pair{int16_t{-24576}, 0.63e6}}) {
    const Sweep sweep = SweepBox(BridgeLinearisationQ{raw, k_q13}, half);
    std::printf(
        "k = %+.5f over +-%.2g codes: worst |s - closed form| %.1f codes (%.2f quotient "
        "steps), max %u cycles\n",
        k_q13 / 8192.0,
        half,
        sweep.worst_codes,
        sweep.worst_codes / step_codes,
        sweep.max_cycles);
    EXPECT_LE(sweep.worst_codes, 4.0 * step_codes) << k_q13;
    EXPECT_EQ(sweep.flags, 0) << k_q13;
    EXPECT_LE(sweep.max_cycles, 250u) << k_q13;
  }
}

// k = 0 is the code itself, bit for bit, at a few cycles.
TEST(BridgeLinearisation, ZeroCurvatureIsTheCodeItself) {
  const BridgeLinearisationQ off{InputNormQ31{0, 23}, 0};
  for (int32_t y : {0, 1, -1, 6710886, 16777215, -16777215}) {
    DspEngine engine;
    uint16_t flags = 0;
    EXPECT_EQ(LinearisedBridgeCode(&engine, off, y, &flags), y);
    EXPECT_EQ(flags, 0);
    EXPECT_LE(engine.cycles(), 8u);
  }
}

// Outside the normalisation (|v| >= 1), or beyond where the quadratic turns (r < 0): flagged, and
// the result stays a finite code at the box's edge rather than wrapping.
TEST(BridgeLinearisation, FlagsCodesOutsideItsDomain) {
  const BridgeLinearisationQ q{InputNormQ31{6710886, 21}, 15565};  // r = 0 at v = -0.526
  const int32_t origin = q.raw_norm.centre;
  for (int32_t y : {origin - 1200000, origin + (INT32_C(1) << 21) + 5}) {
    DspEngine engine;
    uint16_t flags = 0;
    const int32_t s = LinearisedBridgeCode(&engine, q, y, &flags);
    EXPECT_EQ(flags & kFlagInputSaturated, kFlagInputSaturated) << y;
    EXPECT_LT(std::abs(s - origin), INT32_C(1) << 22) << y;
  }
}

TEST(BridgeLinearisation, BlockWordsRoundTripAndRefusals) {
  const BridgeLinearisationQ q{InputNormQ31{6710886, 21}, -12345};
  int16_t words[kBridgeLinearisationWords];
  BridgeLinearisationToWords(q, words);
  BridgeLinearisationQ back{};
  ASSERT_EQ(BridgeLinearisationFromWords(words, &back), ConstantsStatus::kOk);
  EXPECT_EQ(back.raw_norm.centre, q.raw_norm.centre);
  EXPECT_EQ(back.raw_norm.shift, q.raw_norm.shift);
  EXPECT_EQ(back.curvature_q13, q.curvature_q13);
  const BridgeLinearisationQ unchanged = back;
  for (const BridgeLinearisationQ& bad : {BridgeLinearisationQ{InputNormQ31{6710886, 25}, 1},
                                          BridgeLinearisationQ{InputNormQ31{1 << 24, 21}, 1},
                                          BridgeLinearisationQ{InputNormQ31{-(1 << 24), 21}, 1}}) {
    BridgeLinearisationToWords(bad, words);
    EXPECT_EQ(BridgeLinearisationFromWords(words, &back), ConstantsStatus::kOutOfRange);
    EXPECT_EQ(back.curvature_q13, unchanged.curvature_q13);
    EXPECT_EQ(back.raw_norm.shift, unchanged.raw_norm.shift);
  }
}

}  // namespace
}  // namespace adahrs::firmware_model
