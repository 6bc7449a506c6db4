// SlowNoiseVariance against the statistics of the process it describes: the variance of a
// contrast between two stretches far apart, over many realisations of a known noise, and the
// estimate made from each realisation alone.
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "diagnosis/slow_noise.h"

namespace adahrs::diagnosis {
namespace {

struct Outcome {
  double true_var = 0.0;  // of the contrast over the realisations
  double mean_estimate = 0.0;
};

// Twenty segments of 50 one-second cells, starting 100 s apart; the contrast is the mean of the
// last ten minus that of the first ten. Noise: white of `white_sd` per cell plus a random walk of
// `walk_sd` per root second.
Outcome Realise(double white_sd, double walk_sd) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n01(0.0, 1.0);
  constexpr int kRealisations = 400;
  double sum = 0.0, sum2 = 0.0, est = 0.0;
  for (int r = 0; r < kRealisations; ++r) {
    std::vector<SlowNoiseCell> cells;
    double walk = 0.0, t_prev = 0.0, contrast = 0.0;
    for (int seg = 0; seg < 20; ++seg) {
      for (int i = 0; i < 50; ++i) {
        const double t = seg * 100.0 + i;
        walk += walk_sd * std::sqrt(t - t_prev) * n01(rng);
        t_prev = t;
        const double y = walk + white_sd * n01(rng);
        const double a = (seg < 10 ? -1.0 : 1.0) / 500.0;
        contrast += a * y;
        cells.push_back({0, seg, t, y, white_sd * white_sd, a});
      }
    }
    sum += contrast;
    sum2 += contrast * contrast;
    est += SlowNoiseVariance(cells, 0.0);
  }
  const double mean = sum / kRealisations;
  return {sum2 / kRealisations - mean * mean, est / kRealisations};
}

TEST(SlowNoise, WhiteNoiseAloneGivesTheWhiteVariance) {
  const Outcome o = Realise(1.0, 0.0);
  // 2 / 500. The estimate errs high (about 3 times on white noise alone: the non-decreasing
  // variogram keeps the highest of many noisy lag bins), which costs power, never false findings.
  EXPECT_NEAR(o.true_var, 0.004, 0.0006);
  EXPECT_GT(o.mean_estimate, 0.9 * o.true_var);
  EXPECT_LT(o.mean_estimate, 4.0 * o.true_var);
  std::printf("white: contrast variance %.4g, estimated %.4g\n", o.true_var, o.mean_estimate);
}

TEST(SlowNoise, AWanderBetweenStretchesIsCounted) {
  const Outcome o = Realise(1.0, 0.05);  // the walk's share is 80 x the white's
  EXPECT_GT(o.true_var, 50.0 * 0.004);
  EXPECT_GT(o.mean_estimate, 0.75 * o.true_var);
  EXPECT_LT(o.mean_estimate, 1.5 * o.true_var);
  std::printf("walk: contrast variance %.4g, estimated %.4g\n", o.true_var, o.mean_estimate);
}

}  // namespace
}  // namespace adahrs::diagnosis
