#include "common/gravity.h"
#include "tests/support/error_text.h"

#include <stdexcept>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace adahrs::common {
namespace {

using ::testing::HasSubstr;

TEST(Gravity, EquatorAndPolesAreTheWgs84DefiningValues) {
  // NIMA TR8350.2 table 3.4: γe = 9.7803253359, γp = 9.8321849378 m/s² (physics.md §6 row 12
  // quotes 9.7803 and 9.8322). Somigliana reproduces them to rounding (1e-10 m/s²).
  EXPECT_NEAR(NormalGravityMps2(0.0, 0.0), 9.7803253359, 1e-10);
  EXPECT_NEAR(NormalGravityMps2(90.0, 0.0), 9.8321849378, 1e-9);
  EXPECT_NEAR(NormalGravityMps2(-90.0, 0.0), 9.8321849378, 1e-9);
}

TEST(Gravity, MidLatitudesMatchPublishedValues) {
  // physics.md §6 row 12: 45° ≈ 9.8062, 52° N 9.8125 m/s², quoted to 1e-4 → ±5e-5.
  EXPECT_NEAR(NormalGravityMps2(45.0, 0.0), 9.8062, 5e-5);
  EXPECT_NEAR(NormalGravityMps2(52.0, 0.0), 9.8125, 5e-5);
}

TEST(Gravity, FreeAirGradient) {
  // The classical free-air gradient is −3.086e-6 s⁻² (0.3086 mGal/m); the ellipsoidal formula
  // gives it at 45° to 0.02 % and within 0.1 % everywhere (the gradient scales with γ0).
  const double h_m = 100.0;
  const double gradient45 =
      (NormalGravityMps2(45.0, h_m) - NormalGravityMps2(45.0, -h_m)) / (2.0 * h_m);
  EXPECT_NEAR(gradient45, -3.086e-6, 3.086e-6 * 2e-4);
  for (double lat_deg : {0.0, 30.0, 60.0, 90.0}) {
    const double gradient =
        (NormalGravityMps2(lat_deg, h_m) - NormalGravityMps2(lat_deg, -h_m)) / (2.0 * h_m);
    EXPECT_NEAR(gradient, -3.086e-6, 3.086e-6 * 1e-3) << lat_deg;
  }
}

TEST(Gravity, SymmetricInLatitude) {
  EXPECT_DOUBLE_EQ(NormalGravityMps2(37.5, 1500.0), NormalGravityMps2(-37.5, 1500.0));
}

template <typename F>
std::string DomainErrorOf(F f) {
  return test_support::ErrorText<std::domain_error>(f);
}

TEST(Gravity, OutOfRangeThrowsNamingTheValue) {
  EXPECT_THAT(DomainErrorOf([] { NormalGravityMps2(91.0, 0.0); }),
              HasSubstr("geodetic_latitude_deg = 91"));
  EXPECT_THAT(DomainErrorOf([] { NormalGravityMps2(45.0, 30000.0); }),
              HasSubstr("height_m = 30000"));
}

}  // namespace
}  // namespace adahrs::common
