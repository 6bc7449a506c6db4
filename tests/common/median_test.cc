// Median: hand-worked samples, and random samples against a full sort (an independent way to the
// element of rank n/2).
#include "common/median.h"

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "common/random.h"

namespace adahrs::common {
namespace {

TEST(Median, OddCountIsTheMiddleValue) {
  EXPECT_EQ(Median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(Median({5.0, -1.0, 9.0, 7.0, 0.5}), 5.0);
  EXPECT_EQ(Median({42.0}), 42.0);
}

TEST(Median, EvenCountIsTheUpperMiddleValueNotTheMean) {
  EXPECT_EQ(Median({4.0, 1.0, 3.0, 2.0}), 3.0);  // the mean of the middle two would be 2.5
  EXPECT_EQ(Median({10.0, -10.0}), 10.0);
}

TEST(Median, RepeatedValuesCount) {
  EXPECT_EQ(Median({1.0, 1.0, 1.0, 5.0, 9.0}), 1.0);
  EXPECT_EQ(Median({2.0, 7.0, 7.0, 7.0}), 7.0);
}

TEST(Median, EmptySampleIsZero) { EXPECT_EQ(Median({}), 0.0); }

TEST(Median, AgreesWithAFullSortOnRandomSamples) {
  Rng rng(20261206);
  for (int size = 1; size <= 40; ++size) {
    std::vector<double> v;
    for (int i = 0; i < size; ++i) v.push_back(rng.Normal());
    std::vector<double> sorted = v;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(Median(v), sorted[sorted.size() / 2]) << size;
  }
}

}  // namespace
}  // namespace adahrs::common
