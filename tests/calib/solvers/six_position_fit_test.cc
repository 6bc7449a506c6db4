// Constructed-truth tests of the six-position offset and scale (Eq. 17-20).
#include "calib/solvers/six_position_fit.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/solvers/linear_least_squares.h"

namespace adahrs::calib {
namespace {

using ::testing::HasSubstr;

// Channel truth (duty): offsets near 0 after thermal compensation, scales +-0.04 duty per g with
// the reference's signs (az1 -, ax1 -, ay1 +, az2 +, ax2 +, ay2 -).
constexpr std::array<double, 6> kOffset = {0.003, -0.002, 0.001, -0.004, 0.0005, 0.002};
constexpr std::array<double, 6> kScale = {-0.0394, -0.0399, 0.0396, 0.0386, 0.0391, -0.0389};
constexpr std::array<int, 6> kAxis = {3, 1, 2, 3, 1, 2};
constexpr double kGLocal_mps2 = 9.7949;  // Auburn AL, 33 deg N (gravity.h normal gravity)

std::vector<AccelOrientationMeans> Steps() {
  const double g_l = kGLocal_mps2 / 9.80665;
  std::vector<AccelOrientationMeans> steps;
  for (int axis = 1; axis <= 3; ++axis) {
    for (int sense = 1; sense <= 2; ++sense) {
      AccelOrientationMeans s;
      s.orientation = 10 * axis + sense;
      for (int ch = 0; ch < 6; ++ch) {
        const double f_g = kAxis[ch] == axis ? (sense == 1 ? g_l : -g_l) : 0.0;
        s.t_duty[ch] = kOffset[ch] + kScale[ch] * f_g;
        s.t_duty_se[ch] = 2e-6 * (1 + ch);
      }
      steps.push_back(s);
    }
  }
  return steps;
}

TEST(SixPositionFit, RecoversOffsetAndScaleInStandardG) {
  const auto fit = FitSixPosition(Steps(), kGLocal_mps2);
  for (int ch = 0; ch < 6; ++ch) {
    // Exact data: only rounding of O(0.5) sums (1e-15 duty).
    EXPECT_NEAR(fit[ch].fit.offset_duty, kOffset[ch], 1e-15) << ch;
    EXPECT_NEAR(fit[ch].fit.scale_duty_per_g, kScale[ch], 1e-15) << ch;
    EXPECT_NEAR(fit[ch].inverse_scale_g_per_duty, 1.0 / kScale[ch], 1e-11) << ch;
    // se(O) = sqrt(se+^2 + se-^2) / 2 with equal se: se / sqrt(2); se(S) = that / g_l.
    const double se = 2e-6 * (1 + ch);
    EXPECT_NEAR(fit[ch].offset_se_duty, se / std::sqrt(2.0), 1e-18) << ch;
    EXPECT_NEAR(fit[ch].scale_se_duty_per_g, se / std::sqrt(2.0) / (kGLocal_mps2 / 9.80665), 1e-18);
  }
}

TEST(SixPositionFit, RefusesMissingOrientationNamingTheChannel) {
  auto steps = Steps();
  steps.erase(steps.begin() + 3);  // orientation 22
  EXPECT_THAT([&] { FitSixPosition(steps, kGLocal_mps2); },
              ::testing::ThrowsMessage<DegenerateDesignError>(HasSubstr(
                  "six-position fit: design refused: orientation 22 is missing (channel ay1 "
                  "needs 21 and 22)")));
}

TEST(SixPositionFit, RefusesRepeatedOrientation) {
  auto steps = Steps();
  steps.push_back(steps[0]);
  EXPECT_THAT([&] { FitSixPosition(steps, kGLocal_mps2); },
              ::testing::ThrowsMessage<DegenerateDesignError>(
                  HasSubstr("orientation 11 appears more than once")));
}

TEST(SixPositionFit, RefusesZeroStandardError) {
  auto steps = Steps();
  steps[4].t_duty_se[0] = 0.0;  // orientation 31, az1
  EXPECT_THAT([&] { FitSixPosition(steps, kGLocal_mps2); },
              ::testing::ThrowsMessage<DegenerateDesignError>(
                  HasSubstr("six-position fit of az1: design refused: observation 0")));
}

}  // namespace
}  // namespace adahrs::calib
