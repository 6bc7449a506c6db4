// The specification tables (reference-method.md, thesis Tables 1-5) and the documented
// interpolation rule: stated points exactly, linear between them, held below 60 kt, refused
// outside the operating limits.
#include "calib/acceptance/specification.h"
#include "calib/acceptance/ads_tolerance.h"

#include <stdexcept>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace adahrs::calib {
namespace {

TEST(Specification, StatedPointsAreTheReferenceTables) {
  const Specification s = Specification::Reference();
  EXPECT_EQ(s.accel_mg, 1.0);
  EXPECT_EQ(s.body_rate_dps, 0.015);
  EXPECT_EQ(s.temp_min_c, -40.0);
  EXPECT_EQ(s.temp_max_c, 85.0);
  EXPECT_EQ(s.altitude_ft.At(-1000.0), 15.0);
  EXPECT_EQ(s.altitude_ft.At(0.0), 15.0);
  EXPECT_EQ(s.altitude_ft.At(10000.0), 15.0);
  EXPECT_EQ(s.altitude_ft.At(30000.0), 20.0);
  EXPECT_EQ(s.altitude_ft.At(50000.0), 80.0);
  EXPECT_EQ(s.airspeed_kt.At(60.0), 5.0);
  EXPECT_EQ(s.airspeed_kt.At(100.0), 2.0);
  EXPECT_EQ(s.airspeed_kt.At(300.0), 1.0);
  EXPECT_EQ(s.airspeed_kt.At(450.0), 1.0);
}

TEST(Specification, LinearBetweenPointsHeldBelowTheFirstAirspeed) {
  const Specification s = Specification::Reference();
  EXPECT_DOUBLE_EQ(s.altitude_ft.At(20000.0), 17.5);  // midway 15 -> 20
  EXPECT_DOUBLE_EQ(s.altitude_ft.At(40000.0), 50.0);  // midway 20 -> 80
  EXPECT_DOUBLE_EQ(s.airspeed_kt.At(80.0), 3.5);      // midway 5 -> 2
  EXPECT_DOUBLE_EQ(s.airspeed_kt.At(200.0), 1.5);     // midway 2 -> 1
  EXPECT_EQ(s.airspeed_kt.At(30.0), 5.0);
}

TEST(Specification, OutsideTheOperatingLimitsThereIsNoTolerance) {
  const Specification s = Specification::Reference();
  try {
    s.altitude_ft.At(51000.0);
    FAIL();
  } catch (const std::out_of_range& e) {
    EXPECT_THAT(e.what(),
                ::testing::HasSubstr("altitude 51000 ft is outside the operating limits"));
  }
  EXPECT_THROW(s.airspeed_kt.At(20.0), std::out_of_range);
  EXPECT_THROW(s.altitude_ft.At(-1500.0), std::out_of_range);
}

TEST(Specification, JsonCarriesTheTablesAndTheRule) {
  const nlohmann::json j = Specification::Reference().ToJson();
  EXPECT_EQ(j["altitude_ft"]["points"].size(), 4u);
  EXPECT_EQ(j["airspeed_kt"]["points"][1][1], 2.0);
  EXPECT_THAT(j["altitude_ft"]["interpolation"].get<std::string>(),
              ::testing::HasSubstr("assumption"));
}

// The ADS evaluation keeps its own copy of the tolerance points (with extra report points); both
// copies must give the same tolerance everywhere in the operating limits.
TEST(Specification, AdsEvaluationTolerancesMatchTheSpecification) {
  const Specification s = Specification::Reference();
  for (double alt_ft = -1000.0; alt_ft <= 50000.0; alt_ft += 250.0) {
    EXPECT_DOUBLE_EQ(AltitudeToleranceFt(alt_ft), s.altitude_ft.At(alt_ft)) << alt_ft << " ft";
  }
  for (double cas_kt = 30.0; cas_kt <= 450.0; cas_kt += 2.5) {
    EXPECT_DOUBLE_EQ(AirspeedToleranceKt(cas_kt), s.airspeed_kt.At(cas_kt)) << cas_kt << " kt";
  }
}

}  // namespace
}  // namespace adahrs::calib
