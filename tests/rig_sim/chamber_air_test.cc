#include "rig_sim/chamber_air.h"

#include <cmath>

#include <gtest/gtest.h>

namespace adahrs::rig_sim {
namespace {

TEST(ChamberAir, LargeStepsRampAtTheCapacityLimits) {
  const ChamberAirParams p;
  ChamberAir chamber(p, 25.0);
  // Far from the set point the slope is the cooling capacity: 3.5 °C/min over 5 minutes.
  for (int i = 0; i < 300; ++i) chamber.Step(-40.0, 1.0);
  EXPECT_NEAR(chamber.air_c(), 25.0 - 3.5 * 5.0, 1e-6);
  ChamberAir heating(p, -40.0);
  for (int i = 0; i < 300; ++i) heating.Step(85.0, 1.0);
  EXPECT_NEAR(heating.air_c(), -40.0 + 5.0 * 5.0, 1e-6);
}

TEST(ChamberAir, SettlesInsideTheControlBand) {
  const ChamberAirParams p;
  ChamberAir chamber(p, 25.0);
  double worst_c = 0.0;
  for (int i = 0; i < 4 * 3600; ++i) {
    chamber.Step(65.0, 1.0);
    if (i > 3 * 3600) worst_c = std::max(worst_c, std::abs(chamber.air_c() - 65.0));
  }
  // ±0.3 °C control: the residual cycling reaches but never exceeds the band.
  EXPECT_LE(worst_c, p.control_band_c + 1e-9);
  EXPECT_GT(worst_c, 0.5 * p.control_band_c);
}

TEST(ChamberAir, SetPointsBeyondReachAreClampedToTheChamberLimits) {
  ChamberAirParams p;
  p.min_c = -45.0;
  ChamberAir chamber(p, -44.0);
  for (int i = 0; i < 3600; ++i) chamber.Step(-80.0, 1.0);
  EXPECT_NEAR(chamber.air_c(), -45.0, p.control_band_c + 1e-9);
}

}  // namespace
}  // namespace adahrs::rig_sim
