#include "hil/recording/torn_tail.h"

#include <unistd.h>

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

namespace adahrs::hil {
namespace {

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class TornTailTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("adahrs_torn_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(TornTailTest, CleanFileIsLeftAlone) {
  std::ofstream(dir_ / "imu.csv") << "h\n1\n";
  EXPECT_FALSE(SetAsideTornTail(dir_ / "imu.csv").has_value());
  EXPECT_EQ(ReadAll(dir_ / "imu.csv"), "h\n1\n");
  EXPECT_FALSE(SetAsideTornTail(dir_ / "absent.csv").has_value());
}

TEST_F(TornTailTest, TornBytesMoveAsideAndTheCsvEndsOnItsLastCompleteLine) {
  std::ofstream(dir_ / "imu.csv") << "h\n1,2\n3,";
  const auto first = SetAsideTornTail(dir_ / "imu.csv");
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->filename(), "imu.csv.torn-1");
  EXPECT_EQ(ReadAll(*first), "3,");
  EXPECT_EQ(ReadAll(dir_ / "imu.csv"), "h\n1,2\n");
  std::ofstream(dir_ / "imu.csv", std::ios::app) << "4,5";  // a second crash
  const auto second = SetAsideTornTail(dir_ / "imu.csv");
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->filename(), "imu.csv.torn-2");
  EXPECT_EQ(ReadAll(*second), "4,5");
  EXPECT_EQ(ReadAll(*first), "3,");
}

}  // namespace
}  // namespace adahrs::hil
