// FramesBetween against hand-counted cases of a unit sending every 10 ms with an 8-bit counter:
// consecutive packets, lost packets, the counter's wrap, whole turns the arrival time reveals,
// bursts that share one arrival time, and a packet logged twice.
#include "hil/recording/frame_count.h"

#include <gtest/gtest.h>

namespace adahrs::hil {
namespace {

constexpr double kPeriod_s = 0.01;

TEST(FramesBetween, CountsTheCounterStepAcrossItsWrap) {
  EXPECT_EQ(FramesBetween(10, 11, 0.01, kPeriod_s), 1);
  EXPECT_EQ(FramesBetween(255, 0, 0.01, kPeriod_s), 1);
  EXPECT_EQ(FramesBetween(250, 4, 0.10, kPeriod_s), 10);  // 9 lost across the wrap
}

TEST(FramesBetween, BurstsKeepTheCounterStepWhateverTheArrivalTime) {
  EXPECT_EQ(FramesBetween(7, 8, 0.0, kPeriod_s), 1);  // read in one burst
  EXPECT_EQ(FramesBetween(7, 8, 0.5, kPeriod_s), 1);  // held 0.5 s by a busy host
  EXPECT_EQ(FramesBetween(7, 7, 0.0, kPeriod_s), 0);  // the same packet logged twice
}

TEST(FramesBetween, WholeTurnsComeFromTheArrivalTime) {
  // A 3 s unplug: 300 frames, the counter moved 300 mod 256 = 44.
  EXPECT_EQ(FramesBetween(0, 44, 3.0, kPeriod_s), 300);
  EXPECT_EQ(FramesBetween(0, 44, 3.0 + 0.9, kPeriod_s), 300);  // arrival late by 0.9 s
  EXPECT_EQ(FramesBetween(100, 100, 2.56, kPeriod_s), 256);    // exactly one turn
}

}  // namespace
}  // namespace adahrs::hil
