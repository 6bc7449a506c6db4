// The hysteresis spans of one pressure bridge estimated from its calibration points (no datasheet
// gives a model-1230 part's spans, physics.md section 6). The states are nonlinear in the spans,
// the centre fit is linear given them: a profile search over a grid uniform in log(span), refined
// twice, each candidate scored by the caller's weighted residual sum of squares; each span's
// standard error from the profile's curvature at the optimum.
// Units: pressure span in Pa, thermal span in degC; cost in the caller's units.
// Search grid, standard errors, measured accuracy: docs/calibration-strategies.md ("Hysteresis
// spans from the recording").
// Left out: the spans' correlation and the law's own error (each standard error is along its axis
// with the other held, the law taken as exact); the shape of the law (the spans are those of the
// unit's own operator, unit_hysteresis_operator.h).
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
