#include "calib/executor/interlocks.h"

#include <array>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adahrs_build_paths.h"
#include "calib/sequence/sequence.h"
#include "common/param_reader.h"

namespace adahrs::calib {
namespace {

using ::testing::HasSubstr;

// Raw averages built from the reference's channel signs (reference-method.md "The unit": az1 -z,
// ax1 -x, ay1 +y, az2 +z, ax2 +x, ay2 -y), the ADXL210E's nominal 4 %/g and the ADXRS150's
// 20,971.52 counts/(deg/s) — the datasheet facts, written out here independently of the code.
constexpr std::array<int, 6> kAxis = {2, 0, 1, 2, 0, 1};
constexpr std::array<double, 6> kSign = {-1, -1, +1, +1, +1, -1};

RawAverage AtRest(const Eigen::Vector3d& f_B_g, const std::array<double, 6>& offset_g = {}) {
  RawAverage a;
  a.packets = 100;
  for (int ch = 0; ch < 6; ++ch)
    a.duty_offset[ch] = 0.04 * (kSign[ch] * f_B_g[kAxis[ch]] + offset_g[ch]);
  a.gyro_cnt = {4194304.0, 4194304.0, 4194304.0};
  return a;
}

TEST(Interlocks, UpAxisFollowsTheFixtureCode) {
  EXPECT_EQ(UpAxis_B(11), Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(UpAxis_B(22), Eigen::Vector3d(0, -1, 0));
  EXPECT_EQ(UpAxis_B(31), Eigen::Vector3d(0, 0, 1));
  EXPECT_THROW(UpAxis_B(13), std::invalid_argument);
}

TEST(Interlocks, NominalSpecificForceInvertsTheChannelMap) {
  const Eigen::Vector3d f(0.3, -0.7, 1.0);
  EXPECT_TRUE(NominalSpecificForce_B_g(AtRest(f)).isApprox(f, 1e-12));
}

TEST(Interlocks, FirstCheckCatchesAUnitMountedUpsideDown) {
  EXPECT_TRUE(GravityVerdict(AtRest({0, 0, 1}), 31, nullptr).ok);
  const InterlockVerdict v = GravityVerdict(AtRest({0, 0, -1}), 31, nullptr);
  EXPECT_FALSE(v.ok);
  EXPECT_THAT(v.detail, HasSubstr("orientation 32"));
}

// Offsets of 0.5 g per channel (what the rig's drawn units show) would fool an absolute check;
// the relative one sees only the change, so they cancel.
TEST(Interlocks, RelativeCheckIsBlindToZeroGOffsets) {
  const std::array<double, 6> offsets = {0.5, -0.5, 0.4, -0.6, 0.5, 0.3};
  const GravityReference ref{AtRest(UpAxis_B(11), offsets), 11};
  for (int code : kOrientationCodes) {
    const RawAverage now = AtRest(UpAxis_B(code), offsets);
    EXPECT_TRUE(GravityVerdict(now, code, &ref).ok) << code;
    for (int other : kOrientationCodes) {
      if (other == code) continue;
      EXPECT_FALSE(GravityVerdict(now, other, &ref).ok) << code << " vs " << other;
    }
  }
}

TEST(Interlocks, GyroCheckWantsTheUpAxisGyroWithItsSign) {
  const RawAverage rest = AtRest({0, 0, 1});
  RawAverage jog = rest;
  jog.gyro_cnt[2] += 100.0 * 20971.52;  // +100 deg/s about +z_B
  EXPECT_TRUE(GyroAxisVerdict(rest, jog, 31, 100.0).ok);
  EXPECT_FALSE(GyroAxisVerdict(rest, jog, 32, 100.0).ok);  // upside down: -100 expected
  EXPECT_FALSE(GyroAxisVerdict(rest, jog, 11, 100.0).ok);  // x_B up: gx should have moved
  RawAverage weak = rest;
  weak.gyro_cnt[2] += 30.0 * 20971.52;  // 30 % of the nominal response: not the table's rate
  EXPECT_FALSE(GyroAxisVerdict(rest, weak, 31, 100.0).ok);
}

// A tightened threshold trips where the default does not (docs/executor.md "Interlocks").
TEST(Interlocks, ATightenedGravityToleranceTripsWhereTheDefaultPasses) {
  const GravityReference ref{AtRest(UpAxis_B(11)), 11};
  // In 31 the change should be (−1, 0, +1) g; this unit shows 0.3 g more on y_B (a fixture
  // tilted some 17°), inside the default 0.5 g and outside 0.25 g.
  const RawAverage tilted = AtRest({0.0, 0.3, 1.0});
  EXPECT_TRUE(GravityVerdict(tilted, 31, &ref).ok);
  InterlockThresholds tight;
  tight.relative_tolerance_g = 0.25;
  const InterlockVerdict v = GravityVerdict(tilted, 31, &ref, tight);
  EXPECT_FALSE(v.ok);
  EXPECT_THAT(v.detail, HasSubstr("off by 0.30 g (tolerance 0.25 g)"));
}

TEST(Interlocks, ATightenedGyroResponseBandTripsWhereTheDefaultPasses) {
  const RawAverage rest = AtRest({0, 0, 1});
  RawAverage jog = rest;
  jog.gyro_cnt[2] += 60.0 * 20971.52;  // 60 % of a 100 deg/s jog: inside 50…150 %
  EXPECT_TRUE(GyroAxisVerdict(rest, jog, 31, 100.0).ok);
  InterlockThresholds tight;
  tight.min_gyro_response = 0.7;
  EXPECT_FALSE(GyroAxisVerdict(rest, jog, 31, 100.0, tight).ok);
  RawAverage strong = rest;
  strong.gyro_cnt[2] += 140.0 * 20971.52;  // 140 %: inside the default, above a 1.2 ceiling
  EXPECT_TRUE(GyroAxisVerdict(rest, strong, 31, 100.0).ok);
  tight.max_gyro_response = 1.2;
  EXPECT_FALSE(GyroAxisVerdict(rest, strong, 31, 100.0, tight).ok);
}

TEST(Interlocks, TheStationFileSetsThresholdsAndAttempts) {
  nlohmann::json j = common::ParamReader::LoadFile(std::string(ADAHRS_SOURCE_DIR) +
                                                   "/docs/examples/station-virtual-rig.json");
  const hil::Station plain = hil::Station::FromJson(common::ParamReader(j, "station.json"));
  const InterlockThresholds defaults = ThresholdsForStation(plain);
  EXPECT_EQ(defaults.relative_tolerance_g, 0.5);
  EXPECT_EQ(defaults.first_check_margin_g, 1.0);
  EXPECT_EQ(defaults.min_gyro_response, 0.5);
  EXPECT_EQ(defaults.max_gyro_response, 1.5);
  EXPECT_EQ(InterlockAttemptsForStation(plain, 3), 3);

  j["interlocks"] = {{"relative_tolerance_g", 0.25}, {"min_gyro_response", 0.7}, {"attempts", 1}};
  const hil::Station set = hil::Station::FromJson(common::ParamReader(j, "station.json"));
  const InterlockThresholds t = ThresholdsForStation(set);
  EXPECT_EQ(t.relative_tolerance_g, 0.25);
  EXPECT_EQ(t.first_check_margin_g, 1.0);
  EXPECT_EQ(t.min_gyro_response, 0.7);
  EXPECT_EQ(t.max_gyro_response, 1.5);
  EXPECT_EQ(InterlockAttemptsForStation(set, 3), 1);
  EXPECT_EQ(hil::Station::FromJson(common::ParamReader(set.ToJson(), "again")).ToJson(),
            set.ToJson());

  j["interlocks"] = {{"attempts", 0}};
  EXPECT_THROW(hil::Station::FromJson(common::ParamReader(j, "station.json")), common::ParamError);
  j["interlocks"] = {{"tolerance_g", 0.3}};
  try {
    hil::Station::FromJson(common::ParamReader(j, "station.json"));
    FAIL() << "an unknown interlock key was accepted";
  } catch (const common::ParamError& e) {
    EXPECT_THAT(e.what(), HasSubstr("$.interlocks.tolerance_g"));
  }
}

}  // namespace
}  // namespace adahrs::calib
