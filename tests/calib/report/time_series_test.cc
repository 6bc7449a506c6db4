// The report's min/max decimation (calib/report/time_series.h) on a series whose extremes are
// known: a million samples of a slow sine with one spike keep at most kTimeSeriesBins bins, and
// the envelope's extremes are the data's, the spike included, at its time.
#include "calib/report/time_series.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

namespace adahrs::calib {
namespace {

TEST(DecimatedSeries, AMillionSamplesKeepTheirExtremesInAFewHundredBins) {
  DecimatedSeries series;
  constexpr int kSamples = 1000000;
  constexpr double kPeriod_s = 0.01;
  constexpr int kSpike = 654321;
  double lo = 1e9, hi = -1e9;
  for (int i = 0; i < kSamples; ++i) {
    const double t_s = i * kPeriod_s;
    const double v = i == kSpike ? 7.5 : std::sin(2.0 * M_PI * t_s / 3600.0);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    series.Add(t_s, v);
  }
  std::vector<double> t_s, v;
  series.Envelope(t_s, v);
  ASSERT_FALSE(t_s.empty());
  EXPECT_LE(t_s.size(), 2 * kTimeSeriesBins);
  EXPECT_GE(t_s.size(), kTimeSeriesBins);  // halving leaves at least half the bins in use
  EXPECT_TRUE(std::is_sorted(t_s.begin(), t_s.end()));
  EXPECT_DOUBLE_EQ(*std::max_element(v.begin(), v.end()), hi);
  EXPECT_DOUBLE_EQ(*std::min_element(v.begin(), v.end()), lo);
  // The spike sits in the bin that holds its time.
  const size_t at = static_cast<size_t>(std::max_element(v.begin(), v.end()) - v.begin());
  const double bin_s = 2.0 * (t_s.back() - t_s.front()) / static_cast<double>(t_s.size() - 2);
  EXPECT_NEAR(t_s[at], kSpike * kPeriod_s, bin_s);
  EXPECT_GE(t_s.back(), (kSamples - 1) * kPeriod_s - bin_s);
}

TEST(DecimatedSeries, NonFiniteSamplesAreNotDrawn) {
  DecimatedSeries series;
  series.Add(0.0, 1.0);
  series.Add(0.01, std::nan(""));
  series.Add(std::nan(""), 2.0);
  std::vector<double> t_s, v;
  series.Envelope(t_s, v);
  EXPECT_EQ(v, (std::vector<double>{1.0, 1.0}));
}

}  // namespace
}  // namespace adahrs::calib
