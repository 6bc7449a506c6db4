#include "hil/rig_clock.h"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace adahrs::hil {
namespace {

using ::testing::HasSubstr;

class RigClockTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("adahrs-rig-clock-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

// From the last whole turn of a unit's 8-bit packet counter (256 frames) before it was made:
// 1234 frames are 4 turns (1024) and 210 frames.
TEST_F(RigClockTest, ReadsWhatTheRigPublishesFromTheLastCounterTurnBeforeItWasMade) {
  RigClockWriter writer(dir_ / "clock", 0.01, 250.0);
  writer.Publish(1234);
  const RigClock clock(dir_ / "clock");
  EXPECT_EQ(clock.time_scale(), 250.0);
  EXPECT_DOUBLE_EQ(clock.RigTimeS(), 12.34);
  EXPECT_DOUBLE_EQ(clock.NowS(), 2.10);
  writer.Publish(1534);
  EXPECT_DOUBLE_EQ(clock.NowS(), 5.10);
  writer.Publish(100);
  const RigClock early(dir_ / "clock");
  EXPECT_DOUBLE_EQ(early.NowS(), 1.0);
  const auto clock_of = MakeClock(250.0, (dir_ / "clock").string());
  EXPECT_NE(dynamic_cast<RigClock*>(clock_of.get()), nullptr);
}

TEST_F(RigClockTest, SleepWaitsForTheRigNotForTheWall) {
  RigClockWriter writer(dir_ / "clock", 0.01, 1000.0);
  const RigClock clock(dir_ / "clock");
  std::atomic<bool> woke{false};
  std::thread sleeper([&] {
    clock.SleepS(1.0);  // 1 ms of wall time at the nominal 1000x, but the rig does not move
    woke = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_FALSE(woke.load()) << "slept on the wall clock";
  writer.Publish(99);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_FALSE(woke.load()) << "woke before the rig reached the time";
  writer.Publish(100);
  sleeper.join();
  EXPECT_TRUE(woke.load());
}

TEST_F(RigClockTest, AReplyIsLateOnlyOnceTheHeldRigHasPassedItsTimeToo) {
  RigClockWriter writer(dir_ / "clock", 0.01, 100.0);
  const RigClock clock(dir_ / "clock");
  const ReplyDeadline deadline(clock, 0.5, std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
  EXPECT_FALSE(deadline.Passed()) << "late while the rig was held";
  EXPECT_EQ(deadline.WaitLeft(), std::chrono::milliseconds(10));
  writer.Publish(49);
  EXPECT_FALSE(deadline.Passed());
  writer.Publish(50);
  EXPECT_TRUE(deadline.Passed());
  // On a clock that never pauses, the wall time alone decides.
  const ScaledClock scaled(100.0);
  const ReplyDeadline wall(scaled, 1000.0, std::chrono::milliseconds(20));
  EXPECT_FALSE(wall.Passed());
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  EXPECT_TRUE(wall.Passed());
}

TEST_F(RigClockTest, ARigThatStoppedIsAnErrorNamingTheFile) {
  RigClockWriter writer(dir_ / "clock", 0.01, 100.0);
  writer.Publish(500);
  const RigClock clock(dir_ / "clock", 0.3);
  try {
    clock.SleepS(1.0);
    FAIL() << "slept on a clock that stood still";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr((dir_ / "clock").string()));
    EXPECT_THAT(e.what(), HasSubstr("5.00 s"));
  }
}

TEST_F(RigClockTest, RefusesAMissingOrForeignFile) {
  EXPECT_THROW(RigClock(dir_ / "none"), std::runtime_error);
  std::ofstream(dir_ / "short") << "ADAHRSCK";
  EXPECT_THROW(RigClock(dir_ / "short"), std::runtime_error);
  std::ofstream(dir_ / "foreign") << std::string(64, 'x');
  try {
    RigClock clock(dir_ / "foreign");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("foreign"));
    EXPECT_THAT(e.what(), HasSubstr("not an ADAHRSCK"));
  }
}

}  // namespace
}  // namespace adahrs::hil
