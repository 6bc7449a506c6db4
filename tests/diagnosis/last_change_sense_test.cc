// The sense of the last temperature change against paths whose direction is known by
// construction: ramps, a noisy soak, a step between acquisitions.
#include "diagnosis/last_change_sense.h"

#include <random>

#include <gtest/gtest.h>

namespace adahrs::diagnosis {
namespace {

TEST(LastChangeSense, IsZeroUntilTheFirstChangeThenFollowsRamps) {
  LastChangeSense sense;
  EXPECT_EQ(sense.Next(25.0), 0.0);
  EXPECT_EQ(sense.Next(25.3), 0.0);  // within the band
  EXPECT_EQ(sense.Next(25.6), 1.0);  // 0.6 degC above the lowest so far
  for (double t = 25.6; t < 70.0; t += 0.2) EXPECT_EQ(sense.Next(t), 1.0);
  EXPECT_EQ(sense.Next(70.0), 1.0);  // the peak
  EXPECT_EQ(sense.Next(69.6), 1.0);  // 0.4 below the peak: still after heating
  EXPECT_EQ(sense.Next(69.4), -1.0);
  for (double t = 69.4; t > -20.0; t -= 0.2) EXPECT_EQ(sense.Next(t), -1.0);
}

TEST(LastChangeSense, HoldsThroughSoakNoiseAndTurnsAtAStep) {
  LastChangeSense sense;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise_c(0.0, 0.05);
  for (double t = 25.0; t > -20.0; t -= 0.1) sense.Next(t);
  for (int i = 0; i < 10000; ++i) ASSERT_EQ(sense.Next(-20.0 + noise_c(rng)), -1.0);
  // An unrecorded soak at 25 degC: the next acquisition reads 45 degC higher.
  EXPECT_EQ(sense.Next(25.0), 1.0);
  for (int i = 0; i < 10000; ++i) ASSERT_EQ(sense.Next(25.0 + noise_c(rng)), 1.0);
}

}  // namespace
}  // namespace adahrs::diagnosis
