// The span search (calib/ads_calibration/hysteresis_span_fit.h) on costs whose minimum and
// curvature are known in closed form.
#include "calib/ads_calibration/hysteresis_span_fit.h"

#include <gtest/gtest.h>

#include <cmath>

namespace adahrs::calib {
namespace {

// cost = c0 + k_p (ln p - ln p*)^2 + k_t (ln t - ln t*)^2: minimum c0 at (p*, t*); along ln p the
// curvature is 2 k_p, so one standard error in ln p is sqrt(2 (c0 / dof) / (2 k_p)).
TEST(HysteresisSpanFit, FindsAKnownMinimumAndItsCurvature) {
  constexpr double kP = 31000.0, kT = 12.5, kC0 = 40.0, kKp = 900.0, kKt = 400.0;
  constexpr int kDof = 100;
  auto cost = [&](double p, double t) {
    const double u = std::log(p / kP), v = std::log(t / kT);
    return kC0 + kKp * u * u + kKt * v * v;
  };
  const SpanFit f = FitHysteresisSpans(cost, 20684.0, 20.0, kDof);
  // The final grid's step in ln(span) is ln(16) / 16 / 16: the estimate is within half of it.
  const double half_step = 0.5 * std::log(16.0) / 256.0;
  EXPECT_NEAR(std::log(f.pressure_span / kP), 0.0, half_step);
  EXPECT_NEAR(std::log(f.thermal_span_c / kT), 0.0, half_step);
  EXPECT_FALSE(f.at_search_edge);
  EXPECT_GE(f.cost, kC0);
  EXPECT_LE(f.cost - kC0, (kKp + kKt) * half_step * half_step);
  EXPECT_NEAR(f.cost_at_start, cost(20684.0, 20.0), 1e-9);
  EXPECT_NEAR(f.pressure_span_se / f.pressure_span, std::sqrt(kC0 / kDof / kKp), 1e-3);
  EXPECT_NEAR(f.thermal_span_c_se / f.thermal_span_c, std::sqrt(kC0 / kDof / kKt), 1e-3);
}

TEST(HysteresisSpanFit, SaysWhenTheMinimumIsOutsideTheSearchBox) {
  auto cost = [](double p, double t) { return 1.0 + p + std::abs(std::log(t / 10.0)); };
  const SpanFit f = FitHysteresisSpans(cost, 1000.0, 10.0, 10);
  EXPECT_TRUE(f.at_search_edge);
  EXPECT_NEAR(f.pressure_span, 1000.0 * kSpanSearchMin, 1e-6);
}

TEST(HysteresisSpanFit, AFlatProfileHasAnInfiniteStandardError) {
  auto cost = [](double, double t) { return 5.0 + std::pow(std::log(t / 8.0), 2); };
  const SpanFit f = FitHysteresisSpans(cost, 1000.0, 10.0, 10);
  EXPECT_TRUE(std::isinf(f.pressure_span_se));
  EXPECT_TRUE(std::isfinite(f.thermal_span_c_se));
}

}  // namespace
}  // namespace adahrs::calib
