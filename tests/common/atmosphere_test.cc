#include "common/atmosphere.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/units.h"
#include "tests/support/error_text.h"

namespace adahrs::common {
namespace {

using ::testing::HasSubstr;

// The reference tables quote 0.01 hPa; the brief asks for agreement within 0.01 % of the
// published value, which is looser than the table's rounding (≤ 0.5 Pa) at every altitude here.
constexpr double kTableRelativeTolerance = 1e-4;

struct AltitudePressure {
  double alt_ft;
  double ps_hpa;
};

// shared/physics.md §4.1 reference table and shared/protocols.md §5 check values (the 20 km
// value, 65 616.8 ft rounded up, lies just above the modelled range; it is checked in metres in
// TabulatedConstantsAtLayerBoundaries).
constexpr AltitudePressure kIsaTable[] = {
    {-1000.0, 1050.41},
    {0.0, 1013.25},
    {5000.0, 843.07},
    {10000.0, 696.82},
    {20000.0, 465.63},
    {30000.0, 300.90},
    {36089.24, 226.32},
    {40000.0, 187.54},
    {41000.0, 178.74},
    {50000.0, 115.97},
};

TEST(Atmosphere, StaticPressureMatchesPublishedTable) {
  for (const AltitudePressure& row : kIsaTable) {
    const double expected_pa = common::HpaToPa(row.ps_hpa);
    EXPECT_NEAR(
        IsaStaticPressurePaFromFt(row.alt_ft), expected_pa, kTableRelativeTolerance * expected_pa)
        << "alt_ft " << row.alt_ft;
  }
}

TEST(Atmosphere, PressureAltitudeMatchesPublishedTable) {
  // Inverse direction: 0.01 % of pressure corresponds to at most 3 ft (dh/dp ≤ 1.79 ft/Pa at
  // 50 000 ft, physics.md §4.1, times 0.01 % of 11 597 Pa); allow that in feet.
  for (const AltitudePressure& row : kIsaTable) {
    const double ps_pa = common::HpaToPa(row.ps_hpa);
    const double dh_dp_ft_per_pa = common::MToFt(1.0) * kIsaGasConstant_j_per_kg_k * 288.15 /
                                   (common::kStandardGravity_mps2 * ps_pa);
    EXPECT_NEAR(
        IsaPressureAltitudeFt(ps_pa), row.alt_ft, kTableRelativeTolerance * ps_pa * dh_dp_ft_per_pa)
        << "ps_hpa " << row.ps_hpa;
  }
}

TEST(Atmosphere, TabulatedConstantsAtLayerBoundaries) {
  // physics.md §4.1: T0, T11, p11 = 22 632.04 Pa, p(20 km) = 5 474.88 Pa (quoted to 0.01 Pa;
  // tolerance 0.01 Pa plus the last-digit rounding).
  EXPECT_DOUBLE_EQ(IsaTemperatureK(0.0), 288.15);
  EXPECT_NEAR(IsaTemperatureK(11000.0), 216.65, 1e-12);
  EXPECT_NEAR(IsaTemperatureK(15000.0), 216.65, 1e-12);
  EXPECT_NEAR(IsaTemperatureK(-1000.0), 294.65, 1e-12);
  EXPECT_NEAR(IsaStaticPressurePa(11000.0), 22632.04, 0.015);
  EXPECT_NEAR(IsaStaticPressurePa(20000.0), 5474.88, 0.015);
}

TEST(Atmosphere, LayersJoinContinuously) {
  // Across the tropopause the two branches must agree to rounding (relative 1e-12) plus the
  // true change over the 2 µm step (|dp/dh| = p11·g0/(R·T11) = 3.57 Pa/m there).
  const double below_pa = IsaStaticPressurePa(11000.0 - 1e-6);
  const double above_pa = IsaStaticPressurePa(11000.0 + 1e-6);
  EXPECT_NEAR(below_pa, above_pa, 1e-12 * below_pa + 2e-6 * 3.6);
}

TEST(Atmosphere, AltitudeRoundTrip) {
  // Composition of pow/exp with their inverses: error a few ulp of the altitude scale
  // (44 330 m · 1e-15); 1e-7 m is generous and still far below anything physical.
  for (double alt_m = kIsaMinAltitude_m; alt_m <= kIsaMaxAltitude_m; alt_m += 250.0) {
    EXPECT_NEAR(IsaPressureAltitudeM(IsaStaticPressurePa(alt_m)), alt_m, 1e-7) << alt_m;
  }
  for (double alt_ft = -1000.0; alt_ft <= 65000.0; alt_ft += 1000.0) {
    EXPECT_NEAR(IsaPressureAltitudeFt(IsaStaticPressurePaFromFt(alt_ft)), alt_ft, 1e-6);
  }
}

TEST(Atmosphere, PressureSlopeMatchesTable) {
  // dp/dh from the hydrostatic equation dp/dh = −p·g0/(R·T), evaluated independently, against
  // the table's −3.66 Pa/ft at 0 ft and −0.56 Pa/ft at 50 000 ft (quoted to 0.01 Pa/ft).
  const double h_ft = 1.0;
  const double slope0 = (IsaStaticPressurePaFromFt(h_ft) - IsaStaticPressurePaFromFt(-h_ft)) / 2.0;
  const double slope50 =
      (IsaStaticPressurePaFromFt(50000.0 + h_ft) - IsaStaticPressurePaFromFt(50000.0 - h_ft)) / 2.0;
  EXPECT_NEAR(slope0, -3.66, 0.005);
  EXPECT_NEAR(slope50, -0.56, 0.005);
}

TEST(Atmosphere, SpeedOfSoundAtSeaLevel) {
  // a0 = 340.294 m/s (physics.md §4.1, quoted to 1 mm/s).
  EXPECT_NEAR(SpeedOfSoundMps(288.15), 340.294, 0.0005);
}

std::string DomainErrorOf(double (*f)(double), double x) {
  return test_support::ErrorText<std::domain_error>([&] { f(x); });
}

TEST(Atmosphere, OutOfRangeThrowsNamingTheValue) {
  EXPECT_THAT(DomainErrorOf(IsaStaticPressurePa, 25000.0),
              AllOf(HasSubstr("alt_m = 25000"), HasSubstr("[-5000, 20000]")));
  EXPECT_THAT(DomainErrorOf(IsaTemperatureK, -6000.0), HasSubstr("alt_m = -6000"));
  EXPECT_THAT(DomainErrorOf(IsaStaticPressurePaFromFt, 70000.0), HasSubstr("alt_ft = 70000"));
  EXPECT_THAT(DomainErrorOf(IsaPressureAltitudeM, 1000.0), HasSubstr("ps_pa = 1000"));
  EXPECT_THAT(DomainErrorOf(IsaPressureAltitudeFt, std::nan("")), HasSubstr("ps_pa = nan"));
  EXPECT_THAT(DomainErrorOf(SpeedOfSoundMps, -1.0), HasSubstr("static_temp_k = -1"));
}

}  // namespace
}  // namespace adahrs::common
