#include "calib/ads_calibration/hysteresis_span_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace adahrs::calib {
namespace {

constexpr int kCoarsePoints = 17;
constexpr int kFinePoints = 9;
constexpr int kRefinements = 2;

struct Box {
  double log_p_min, log_p_max, log_t_min, log_t_max;
};

// The best (log p, log t) on an n x n grid over `box`, and the grid's step along each axis.
struct GridBest {
  double log_p = 0.0, log_t = 0.0, cost = std::numeric_limits<double>::infinity();
  double step_p = 0.0, step_t = 0.0;
};

GridBest SearchGrid(const std::function<double(double, double)>& cost, const Box& box, int n) {
  GridBest best;
  best.step_p = (box.log_p_max - box.log_p_min) / (n - 1);
  best.step_t = (box.log_t_max - box.log_t_min) / (n - 1);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double lp = box.log_p_min + i * best.step_p, lt = box.log_t_min + j * best.step_t;
      const double c = cost(std::exp(lp), std::exp(lt));
      if (c < best.cost) {
        best.cost = c;
        best.log_p = lp;
        best.log_t = lt;
      }
    }
  }
  return best;
}

// Standard error of a span from the cost's curvature k in u = log(span) through three points h
// apart: cost ~ c0 + k (u - u0)^2 / 2, and one standard error is where the cost has risen by the
// residual variance c0 / dof, so s_u^2 = 2 (c0 / dof) / k.
double SpanSe(double span, double minus, double centre, double plus, double h, int dof) {
  const double curvature = (minus - 2.0 * centre + plus) / (h * h);
  const double variance = centre / dof;
  if (!(curvature > 0.0) || !(variance > 0.0)) return std::numeric_limits<double>::infinity();
  const double se_log = std::sqrt(2.0 * variance / curvature);
  return span * se_log;  // d span = span d(log span)
}

}  // namespace

SpanFit FitHysteresisSpans(const std::function<double(double, double)>& cost,
                           double start_pressure_span,
                           double start_thermal_span_c,
                           int dof,
                           double max_pressure_span) {
  const double lp0 = std::log(start_pressure_span), lt0 = std::log(start_thermal_span_c);
  const double lo = std::log(kSpanSearchMin), hi = std::log(kSpanSearchMax);
  const double lp_max = std::min(lp0 + hi, std::log(max_pressure_span));
  const Box outer{lp0 + lo, std::max(lp0 + lo, lp_max), lt0 + lo, lt0 + hi};
  GridBest best = SearchGrid(cost, outer, kCoarsePoints);
  for (int r = 0; r < kRefinements; ++r) {
    const Box around{std::max(outer.log_p_min, best.log_p - best.step_p),
                     std::min(outer.log_p_max, best.log_p + best.step_p),
                     std::max(outer.log_t_min, best.log_t - best.step_t),
                     std::min(outer.log_t_max, best.log_t + best.step_t)};
    const GridBest next = SearchGrid(cost, around, kFinePoints);
    if (next.cost <= best.cost) best = next;
    best.step_p = next.step_p;
    best.step_t = next.step_t;
  }
  SpanFit out;
  out.pressure_span = std::exp(best.log_p);
  out.thermal_span_c = std::exp(best.log_t);
  out.cost = best.cost;
  out.cost_at_start = cost(start_pressure_span, start_thermal_span_c);
  const double edge = 1e-9;
  out.at_search_edge = best.log_p < outer.log_p_min + edge || best.log_p > outer.log_p_max - edge ||
                       best.log_t < outer.log_t_min + edge || best.log_t > outer.log_t_max - edge;
  const double hp = best.step_p, ht = best.step_t;
  out.pressure_span_se = SpanSe(out.pressure_span,
                                cost(std::exp(best.log_p - hp), out.thermal_span_c),
                                best.cost,
                                cost(std::exp(best.log_p + hp), out.thermal_span_c),
                                hp,
                                dof);
  out.thermal_span_c_se = SpanSe(out.thermal_span_c,
                                 cost(out.pressure_span, std::exp(best.log_t - ht)),
                                 best.cost,
                                 cost(out.pressure_span, std::exp(best.log_t + ht)),
                                 ht,
                                 dof);
  return out;
}

}  // namespace adahrs::calib
