// The chamber wait's measured remaining time (calib/executor/chamber_eta.h) on made-up process
// values whose end time is known in closed form: a straight ramp, a ramp whose rate changes, an
// exponential settling.
#include "calib/executor/chamber_eta.h"

#include <cmath>

#include <gtest/gtest.h>

namespace adahrs::calib {
namespace {

constexpr double kRateCPerS = 2.0 / 60.0;

// 2 degC/min from 0 to 25 degC, band 1 degC, soak 300 s: in the band at 720 s, done at 1020 s.
TEST(ChamberEta, AStraightRampGivesTheTimeLeft) {
  ChamberEta eta(25.0, 1.0, 300.0);
  for (double t_s = 0.0; t_s <= 600.0; t_s += 5.0) {
    eta.Observe(t_s, t_s * kRateCPerS, -1.0);
    if (t_s < kChamberMinWindowS || t_s / 5.0 + 1.0 < kChamberMinReadings) {
      EXPECT_FALSE(eta.RemainingS().has_value()) << t_s;  // too little evidence yet
    } else {
      ASSERT_TRUE(eta.RemainingS().has_value()) << t_s;
      EXPECT_NEAR(*eta.RemainingS(), 1020.0 - t_s, 1e-6) << t_s;
    }
  }
}

TEST(ChamberEta, TheRateIsTheRecentOneNotTheAverage) {
  // 0.5 degC/min for 10 min, then 2 degC/min: after 3 more minutes the estimate uses the new rate.
  ChamberEta eta(-30.0, 0.5, 0.0);
  double pv_c = 25.0;
  for (double t_s = 0.0; t_s <= 780.0; t_s += 10.0) {
    eta.Observe(t_s, pv_c, -1.0);
    pv_c -= (t_s < 600.0 ? 0.5 : 2.0) / 60.0 * 10.0;
  }
  const double pv_now_c = 25.0 - 5.0 - 2.0 * 3.0;  // at 780 s: 10 min at 0.5, 3 min at 2 degC/min
  const double left_s = (pv_now_c - (-30.0) - 0.5) / (2.0 / 60.0);
  ASSERT_TRUE(eta.RemainingS().has_value());
  EXPECT_NEAR(*eta.RemainingS(), left_s, 0.02 * left_s);
}

// Settling onto the set point: e = 12 exp(-t / 150 s) degC, band 0.5 degC, soak 60 s: in the band
// at 150 ln 24 = 476.7 s.
TEST(ChamberEta, ASettlingApproachGivesTheTimeLeft) {
  ChamberEta eta(40.0, 0.5, 60.0);
  const double in_band_s = 150.0 * std::log(24.0);
  for (double t_s = 0.0; t_s <= 400.0; t_s += 5.0) {
    eta.Observe(t_s, 40.0 - 12.0 * std::exp(-t_s / 150.0), -1.0);
    if (t_s >= kChamberMinWindowS && t_s / 5.0 + 1.0 >= kChamberMinReadings) {
      ASSERT_TRUE(eta.RemainingS().has_value()) << t_s;
      EXPECT_NEAR(*eta.RemainingS(), in_band_s + 60.0 - t_s, 1e-6) << t_s;
    }
  }
}

TEST(ChamberEta, InsideTheBandOnlyTheSoakIsLeft) {
  ChamberEta eta(25.0, 1.0, 300.0);
  eta.Observe(1000.0, 24.6, 900.0);
  EXPECT_DOUBLE_EQ(*eta.RemainingS(), 200.0);
  eta.Observe(1300.0, 24.9, 900.0);
  EXPECT_DOUBLE_EQ(*eta.RemainingS(), 0.0);
}

TEST(ChamberEta, AChamberMovingAwayGivesNoEstimate) {
  ChamberEta eta(25.0, 1.0, 60.0);
  for (double t_s = 0.0; t_s <= 120.0; t_s += 10.0) eta.Observe(t_s, 20.0 - t_s / 60.0, -1.0);
  EXPECT_FALSE(eta.RemainingS().has_value());
}

}  // namespace
}  // namespace adahrs::calib
