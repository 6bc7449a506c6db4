// FramesBetween against hand-counted cases of a unit sending every 10 ms with an 8-bit counter:
// consecutive packets, lost packets, the counter's wrap, whole turns the arrival time reveals,
// bursts that share one arrival time, and a packet logged twice. FrameCounter against a unit's
// true frame index through bursts and gaps longer than a counter turn.
#include "hil/recording/frame_count.h"

#include <vector>

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

// A unit sending every 10 ms, read by a host in bursts of up to 80 packets that share one arrival
// time (a fast rig), with gaps of exactly one counter turn (2.56 s: the counter shows the same
// value) and of 3.7 s (370 frames, 114 mod 256): the counted frame is the true one, never short
// by a multiple of 256.
TEST(FrameCounter, CountsTheTrueFrameThroughBurstsAndLongGaps) {
  std::vector<int64_t> frames;
  for (int64_t f = 1000; f < 1600; ++f) frames.push_back(f);
  for (int64_t f = 1856; f < 2000; ++f) frames.push_back(f);  // 256 frames unheard
  for (int64_t f = 2370; f < 3000; ++f) frames.push_back(f);  // 370 frames unheard
  FrameCounter counter;
  int64_t first = -1;
  for (size_t i = 0; i < frames.size(); ++i) {
    // Arrival: the end of the burst of 80 frames the packet falls in.
    const double t_s = static_cast<double>((frames[i] / 80 + 1) * 80) * kPeriod_s;
    const int64_t counted = counter.Next(static_cast<uint32_t>(frames[i] % 256), t_s);
    if (first < 0) first = counted;
    EXPECT_EQ(counted - first, frames[i] - frames[0]) << "true frame " << frames[i];
    EXPECT_EQ(counted % 256, frames[i] % 256);
  }
}

// The first frame is the one nearest the arrival time whose value modulo 256 is the counter, so
// the sample time frame * 10 ms stays within 1.28 s of the arrival time.
TEST(FrameCounter, TheFirstFrameIsNearItsArrivalTime) {
  EXPECT_EQ(FrameCounter().Next(5, 10.0), 1029);  // 1000 frames: 1029 = 4 * 256 + 5
  EXPECT_EQ(FrameCounter().Next(200, 0.0), 200);  // never negative
  EXPECT_EQ(FrameCounter(FrameState{1029, 5, 10.0}).Next(6, 10.0), 1030);  // seeded: continues
}

}  // namespace
// With a lockstep rig's packet index, the step is the index difference whatever the arrival
// times say: a reader held 6 s (more than two counter turns, no new arrival time to tell) then
// reading a burst still counts every frame; an index that went back (a new rig) falls back to
// the counter and the time.
TEST(FrameCounter, StepsByTheRigsPacketIndexWhenItHasOne) {
  FrameCounter counter;
  const int64_t first = counter.Next(10, 0.1, 10);
  EXPECT_EQ(counter.Next(11, 0.11, 11) - first, 1);
  // 700 packets later (700 mod 256 = 188), all read at one instant 0.2 s after the last.
  EXPECT_EQ(counter.Next((11 + 700) % 256, 0.31, 711) - first, 701);
  EXPECT_EQ(counter.Next((11 + 701) % 256, 0.31, 712) - first, 702);
  // A new rig's index 3: the counter's step from 200 (712 mod 256) to 3 is 59, and 0.59 s
  // passed, so no whole turn.
  EXPECT_EQ(counter.Next(3, 0.90, 3) - first, 702 + 59);
}

}  // namespace adahrs::hil
