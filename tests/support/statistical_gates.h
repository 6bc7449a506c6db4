// The suite's statistical gates (docs/testing.md "The rules"), each computed from a stated level
// and the suite's false-failure rate, never from the count a run gave; and the bound a test puts
// on a standard error the code under test reports before it leans on it. The distributions are
// Boost.Math's, not the diagnoser's.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>

namespace adahrs::testing {

// The chance that one statistical gate fails on code that meets its stated level.
inline constexpr double kFalseFailureRate = 1e-3;

// The most of `n` independent trials that may show an event of stated probability `p` each: the
// smallest k with P(X >= k + 1 | n, p) below `false_failure`. For false findings over clean units
// p is the stated per-unit level; for misses p is one minus the stated power; for components
// outside 3 standard errors p is the normal's two-sided 2.7e-3.
inline int AllowedCount(int n, double p, double false_failure = kFalseFailureRate) {
  if (n <= 0 || p <= 0.0) return 0;
  if (p >= 1.0) return n;
  const boost::math::binomial_distribution<double> b(n, p);
  for (int k = 0; k < n; ++k) {
    if (boost::math::cdf(boost::math::complement(b, k)) < false_failure) return k;
  }
  return n;
}

// Two-sided probability that an honest estimate lies beyond `k` standard errors of its truth.
inline double OutsideSigmas(double k) {
  return 2.0 * boost::math::cdf(boost::math::normal_distribution<double>(), -k);
}

// The fewest of `n` components that must lie within 3 standard errors of the truth when the
// errors are honest.
inline int RequiredWithinThreeSe(int n) { return n - AllowedCount(n, OutsideSigmas(3.0)); }

// A reported standard error bounded from above by the truth: an inflated error makes "within 3
// SE" and every detection limit easy, so a test that leans on one checks it is not inflated. Over
// the findings added, z = (estimate - truth) / se per component; the mean of z^2 is about 1 for an
// honest error and about 1 / c^2 for one c times too large. The floor is the lower
// kFalseFailureRate quantile of chi^2_n / n with n the findings, not the components: a finding's
// components may be correlated, and one degree of freedom per finding is the conservative side. A
// model-form error the truth carries (an allowance in "3 SE + 15 %") only raises the mean, so the
// check holds there too; a too small error is the "within 3 SE" count's to catch.
class StandardErrorBound {
 public:
  explicit StandardErrorBound(std::string what) : what_(std::move(what)) {}

  // One finding with one component.
  void Add(double estimate, double standard_error, double truth) {
    AddComponent(estimate, standard_error, truth);
    ++findings_;
  }
  // Components of one finding: call AddComponent for each, then EndFinding.
  void AddComponent(double estimate, double standard_error, double truth) {
    const double z = (estimate - truth) / standard_error;
    sum_z2_ += z * z;
    ++components_;
  }
  void EndFinding() { ++findings_; }

  int findings() const { return findings_; }
  double MeanZ2() const { return components_ > 0 ? sum_z2_ / components_ : 0.0; }
  // The floor on MeanZ2 (0 with no finding).
  double Floor() const {
    if (findings_ == 0) return 0.0;
    const boost::math::chi_squared_distribution<double> chi2(findings_);
    return boost::math::quantile(chi2, kFalseFailureRate) / findings_;
  }
  // Expects at least `min_findings` and the mean of z^2 at or above the floor. An error the docs
  // state to be `documented_inflation` times the scatter (a deliberate worst-case term) is held
  // there: the floor is divided by its square.
  void Expect(int min_findings, double documented_inflation = 1.0) const {
    const double floor = Floor() / (documented_inflation * documented_inflation);
    std::printf(
        "%s: %d findings, %d components: mean z^2 %.3g, floor %.3g (errors %.2f times the "
        "estimates' scatter about the truth; more than %.2f times fails)\n",
        what_.c_str(),
        findings_,
        components_,
        MeanZ2(),
        floor,
        MeanZ2() > 0.0 ? std::sqrt(1.0 / MeanZ2()) : INFINITY,
        floor > 0.0 ? std::sqrt(1.0 / floor) : INFINITY);
    EXPECT_GE(findings_, min_findings) << what_;
    EXPECT_GE(MeanZ2(), floor) << what_ << ": the standard errors are larger than the scatter of "
                               << "the estimates about the truth allows";
  }

 private:
  std::string what_;
  int findings_ = 0;
  int components_ = 0;
  double sum_z2_ = 0.0;
};

}  // namespace adahrs::testing
