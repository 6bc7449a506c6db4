#include "rig_sim/fixture_orientation.h"

#include <gtest/gtest.h>

namespace adahrs::rig_sim {
namespace {

TEST(FixtureOrientation, CodesNameTheUpAxisAndSense) {
  EXPECT_EQ(UpAxis_B(11), Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(UpAxis_B(12), Eigen::Vector3d(-1, 0, 0));
  EXPECT_EQ(UpAxis_B(21), Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(UpAxis_B(22), Eigen::Vector3d(0, -1, 0));
  EXPECT_EQ(UpAxis_B(31), Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(UpAxis_B(32), Eigen::Vector3d(0, 0, -1));
}

TEST(FixtureOrientation, InvalidCodesAreRefusedByName) {
  for (int code : {0, 10, 13, 33, 41, -11}) {
    EXPECT_FALSE(IsValidOrientation(code));
    try {
      UpAxis_B(code);
      FAIL() << code;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::to_string(code)), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace adahrs::rig_sim
