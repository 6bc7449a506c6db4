#include "common/random.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace adahrs::common {
namespace {

double NormalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// Kolmogorov–Smirnov against the exact normal CDF: with n = 10^6 the 0.1 % critical value of
// sqrt(n)·D is 1.95, so D < 1.95e-3 passes a correct generator 999 times in 1000, and a generator
// with a layer-table error (even 1 % of one layer's mass) fails.
TEST(Rng, NormalPassesKolmogorovSmirnov) {
  Rng rng(12345);
  std::vector<double> z(1000000);
  for (double& v : z) v = rng.Normal();
  std::sort(z.begin(), z.end());
  double d = 0.0;
  const double n = static_cast<double>(z.size());
  for (size_t i = 0; i < z.size(); ++i) {
    const double cdf = NormalCdf(z[i]);
    d = std::max({d, std::abs(cdf - i / n), std::abs((i + 1) / n - cdf)});
  }
  EXPECT_LT(d, 1.95e-3);
}

TEST(Rng, NormalMomentsAndTails) {
  Rng rng(777);
  const int n = 4000000;
  double sum = 0, sum2 = 0, sum4 = 0;
  int beyond3 = 0, beyond4 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = rng.Normal();
    sum += x;
    sum2 += x * x;
    sum4 += x * x * x * x;
    beyond3 += std::abs(x) > 3.0;
    beyond4 += std::abs(x) > 4.0;
  }
  const double mean = sum / n, var = sum2 / n - mean * mean;
  EXPECT_NEAR(mean, 0.0, 5.0 / std::sqrt(n));             // 5 sigma of the mean
  EXPECT_NEAR(var, 1.0, 5.0 * std::sqrt(2.0 / n));        // 5 sigma of the variance
  EXPECT_NEAR(sum4 / n, 3.0, 5.0 * std::sqrt(96.0 / n));  // kurtosis, var(x^4) = 96
  // Tail masses: P(|z| > 3) = 2.6998e-3, P(|z| > 4) = 6.3342e-5; 5-sigma binomial bounds.
  const double p3 = 2.6998e-3, p4 = 6.3342e-5;
  EXPECT_NEAR(beyond3, p3 * n, 5 * std::sqrt(p3 * n));
  EXPECT_NEAR(beyond4, p4 * n, 5 * std::sqrt(p4 * n));
}

// NormalPair: each half of the 64-bit word is its own ziggurat draw (25-bit value). Each half must
// be normal on its own (KS as above, same critical value, one test per half) and the two halves
// independent of each other.
TEST(Rng, NormalPairHalvesPassKolmogorovSmirnov) {
  Rng rng(24680);
  std::vector<double> first(1000000), second(1000000);
  for (size_t i = 0; i < first.size(); ++i) {
    const std::array<double, 2> z = rng.NormalPair();
    first[i] = z[0];
    second[i] = z[1];
  }
  for (std::vector<double>* half : {&first, &second}) {
    std::vector<double>& z = *half;
    std::sort(z.begin(), z.end());
    double d = 0.0;
    const double n = static_cast<double>(z.size());
    for (size_t i = 0; i < z.size(); ++i) {
      const double cdf = NormalCdf(z[i]);
      d = std::max({d, std::abs(cdf - i / n), std::abs((i + 1) / n - cdf)});
    }
    EXPECT_LT(d, 1.95e-3);
  }
}

TEST(Rng, NormalPairMomentsTailsAndIndependence) {
  Rng rng(1357);
  const int pairs = 2000000;
  const int n = 2 * pairs;
  double sum = 0, sum2 = 0, sum4 = 0, cross = 0, cross_sq = 0;
  int beyond3 = 0, beyond4 = 0;
  for (int i = 0; i < pairs; ++i) {
    const std::array<double, 2> z = rng.NormalPair();
    for (const double x : z) {
      sum += x;
      sum2 += x * x;
      sum4 += x * x * x * x;
      beyond3 += std::abs(x) > 3.0;
      beyond4 += std::abs(x) > 4.0;
    }
    cross += z[0] * z[1];
    cross_sq += (z[0] * z[0] - 1.0) * (z[1] * z[1] - 1.0);
  }
  const double mean = sum / n, var = sum2 / n - mean * mean;
  EXPECT_NEAR(mean, 0.0, 5.0 / std::sqrt(n));
  EXPECT_NEAR(var, 1.0, 5.0 * std::sqrt(2.0 / n));
  EXPECT_NEAR(sum4 / n, 3.0, 5.0 * std::sqrt(96.0 / n));
  const double p3 = 2.6998e-3, p4 = 6.3342e-5;
  EXPECT_NEAR(beyond3, p3 * n, 5 * std::sqrt(p3 * n));
  EXPECT_NEAR(beyond4, p4 * n, 5 * std::sqrt(p4 * n));
  // Independent halves: E[z0·z1] = 0 with variance 1, E[(z0² − 1)(z1² − 1)] = 0 with variance 4
  // (the second catches halves that share a layer or a magnitude); 5-sigma bounds.
  EXPECT_NEAR(cross / pairs, 0.0, 5.0 / std::sqrt(pairs));
  EXPECT_NEAR(cross_sq / pairs, 0.0, 5.0 * 2.0 / std::sqrt(pairs));
}

TEST(Rng, NormalPairSameSeedSamePairs) {
  Rng a(3), b(3);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(a.NormalPair(), b.NormalPair());
}

TEST(Rng, SameSeedSameStreamDerivedStreamsDiffer) {
  Rng a(1), b(1), c(Rng::Derive(1, 0)), d(Rng::Derive(1, 1));
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(a.Normal(), b.Normal());
  EXPECT_NE(c.NextU64(), d.NextU64());
}

TEST(Rng, ToleranceDrawsStayInsideTheTolerance) {
  Rng rng(5);
  double sum2 = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double x = rng.Tolerance(10.0, 0.3);
    ASSERT_LE(std::abs(x - 10.0), 0.3);
    sum2 += (x - 10.0) * (x - 10.0);
  }
  // A normal with sigma = tol/3 truncated at 3 sigma has variance 0.9733·sigma².
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.1 * std::sqrt(0.9733), 0.002);
}

}  // namespace
}  // namespace adahrs::common
