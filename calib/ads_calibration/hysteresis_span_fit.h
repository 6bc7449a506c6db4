// The hysteresis spans of one pressure bridge estimated from its calibration points. No datasheet
// gives a model-1230 part's spans (physics.md section 6: estimated), and the surface's error
// grows with the distance between the spans the operators assume and the part's own: so the
// spans are the values that let the centre fit (surface plus gains times the states) explain the
// points best. The states are nonlinear in the spans, the fit is linear given them: a profile
// search, each candidate scored by the caller's weighted residual sum of squares.
// Search: the spans between kSpanSearchMin and kSpanSearchMax times the starting values, on a
// 17 x 17 grid uniform in log(span), then refined twice on 9 x 9 grids of a quarter of the last
// step around the best; each span's standard error from the profile's curvature in log(span) at
// the optimum (a parabola through the best and its two neighbours along that axis), in the
// units of the cost: cost / (points - parameters) is the residual variance, and an increase of
// that much is one standard error.
// Left out: the spans' correlation and the law's own error (each standard error is along its
// axis with the other held and takes the law as exact: on the demo's unit the thermal spans came
// out 3-4 % from the truth, 8-10 of these standard errors);
// the shape of the law (the spans are those of the unit's own operator,
// unit_hysteresis_operator.h: a bridge on another law gets the spans that fit its points best,
// and the residual says how far that is).
#pragma once

#include <functional>
#include <limits>

namespace adahrs::calib {

inline constexpr double kSpanSearchMin = 0.25;
inline constexpr double kSpanSearchMax = 4.0;

struct SpanFit {
  double pressure_span = 0.0;  ///< in the pressure's unit (Pa)
  double thermal_span_c = 0.0;
  double pressure_span_se = 0.0;  ///< one standard error; infinite when the profile is flat
  double thermal_span_c_se = 0.0;
  double cost = 0.0;            ///< at the estimate
  double cost_at_start = 0.0;   ///< at the starting spans
  bool at_search_edge = false;  ///< the estimate lies on the search box's boundary
};

/// Minimises `cost(pressure_span, thermal_span_c)` as described above, from the starting spans;
/// `dof` = points - fitted parameters (> 0) scales the standard errors. `max_pressure_span`, when
/// given, lowers the box's pressure bound: a span longer than the pressure travel the points made
/// leaves every state on its virgin-like quadratic start, which the surface's own curvature can
/// mimic, so the search would trade one for the other.
SpanFit FitHysteresisSpans(const std::function<double(double, double)>& cost,
                           double start_pressure_span,
                           double start_thermal_span_c,
                           int dof,
                           double max_pressure_span = std::numeric_limits<double>::infinity());

}  // namespace adahrs::calib
