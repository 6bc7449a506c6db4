#include "sensor_sim/im3_geometry.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/imu_layout.h"
#include "common/units.h"

namespace adahrs::sensor_sim {
namespace {

// The body axis and sign each channel senses, from the reference scale-factor signs
// (reference-method.md: az1 −, ax1 −, ay1 +, az2 +, ax2 +, ay2 −).
struct Expected {
  int body_axis;
  double sign;
};
constexpr std::array<Expected, 6> kReferenceChannels = {Expected{2, -1},
                                                        Expected{0, -1},
                                                        Expected{1, +1},
                                                        Expected{2, +1},
                                                        Expected{0, +1},
                                                        Expected{1, -1}};

TEST(Im3Geometry, NominalChannelsSenseTheReferenceAxesAndSigns) {
  for (int ch = 0; ch < 6; ++ch) {
    const common::ImuChannel& ca = common::kImuChannels[ch];
    const Eigen::Matrix3d r = common::NominalR_CB(ca.package);
    for (int body_axis = 0; body_axis < 3; ++body_axis) {
      const double expected =
          body_axis == kReferenceChannels[ch].body_axis ? kReferenceChannels[ch].sign : 0.0;
      EXPECT_EQ(r(ca.package_axis, body_axis), expected) << common::kAccelChannelNames[ch];
    }
  }
  for (int g = 0; g < 3; ++g) {
    EXPECT_EQ(common::NominalR_GB(g).row(2), Eigen::Vector3d::Unit(g).transpose());
  }
}

TEST(Im3Geometry, EveryPackageFrameIsAProperRotation) {
  const Im3Geometry g = Im3Geometry::Draw(11);
  for (int k = 0; k < 3; ++k) {
    for (const Eigen::Matrix3d& r : {g.R_CB(k), g.R_GB(k)}) {
      EXPECT_NEAR((r * r.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
      EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
    }
  }
}

TEST(Im3Geometry, DrawnMisalignmentStaysWithinOneDegreePerComponent) {
  // ADXL210E alignment error ±1° (physics.md §1.1): every component within ±1°, so the
  // sensitive axis is off its nominal direction by at most √2° (the rotation about the axis itself
  // does not move it), and the cross-coupling terms are of order 0.01 as in the reference Eq.
  // 30–31.
  double max_cross = 0.0;
  for (uint64_t seed = 1; seed <= 200; ++seed) {
    const Im3Geometry g = Im3Geometry::Draw(seed);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(g.accel_misalignment_deg[k].cwiseAbs().maxCoeff(), 1.0);
      const Eigen::Matrix3d delta = g.R_CB(k) * common::NominalR_CB(k).transpose();
      const double angle_deg = common::RadToDeg(std::acos(std::clamp(delta(0, 0), -1.0, 1.0)));
      EXPECT_LE(angle_deg, std::sqrt(2.0) + 1e-9);
      max_cross = std::max(max_cross, std::abs(delta(0, 1)));
    }
  }
  EXPECT_GT(max_cross, 0.005);
  EXPECT_LT(max_cross, common::DegToRad(std::sqrt(2.0)));
}

TEST(Im3Geometry, MisalignmentEffectOffGivesNominal) {
  Im3Geometry g = Im3Geometry::Draw(3);
  EXPECT_GT((g.R_CB(1) - common::NominalR_CB(1)).norm(), 1e-4);
  g.misalignment = false;
  EXPECT_EQ(g.R_CB(1), common::NominalR_CB(1));
  EXPECT_EQ(g.R_GB(2), common::NominalR_GB(2));
}

TEST(Im3Geometry, JsonRoundTripIsExact) {
  const Im3Geometry g = Im3Geometry::Draw(5);
  const nlohmann::json j = g.ToJson();
  EXPECT_EQ(Im3Geometry::FromJson(common::ParamReader(j, "t")), g);
}

TEST(Im3Geometry, OutOfRangeMisalignmentIsRefusedWithPath) {
  nlohmann::json j = Im3Geometry::Typical().ToJson();
  j["gyro_misalignment_deg"][1][2] = 12.0;
  try {
    Im3Geometry::FromJson(common::ParamReader(j, "u.json", "$.geometry"));
    FAIL();
  } catch (const common::ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("$.geometry.gyro_misalignment_deg[1][2]"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace adahrs::sensor_sim
