// Axis tick positions at "nice" steps (1, 2 or 5 times a power of ten) covering a data range, and
// their labels: the usual graph-paper rule (Heckbert, "Nice numbers for graph labels", Graphics
// Gems, 1990). Used by svg_plot.h.
// Logarithmic axes get one tick per decade (DecadeTicks). Left out: date axes, minor log ticks.
#pragma once

#include <string>
#include <vector>

namespace adahrs::calib {

struct AxisTicks {
  double lo = 0.0;    ///< first tick, <= the data minimum
  double hi = 0.0;    ///< last tick, >= the data maximum
  double step = 0.0;  ///< 1, 2 or 5 x 10^k
  std::vector<double> values;
};

/// Ticks covering [min, max] with at most `max_ticks` (>= 2) ticks; an empty or zero-width range
/// is widened to a unit-wide range around the value. Throws std::invalid_argument on non-finite
/// input.
AxisTicks NiceTicks(double min, double max, int max_ticks);

/// Ticks at every whole decade covering [log10_min, log10_max] (both log10 of data values): lo, hi
/// and values are exponents, step is 1; a range inside one decade spans that decade. Throws
/// std::invalid_argument on non-finite input.
AxisTicks DecadeTicks(double log10_min, double log10_max);

/// The label of decade tick `exponent`: 10^exponent as "0.001", "1", "1000", "1e+06".
std::string DecadeLabel(double exponent);

/// A tick label with as many decimals as the step needs ("0.25", "-5", "1e-05" for tiny steps).
std::string TickLabel(double value, double step);

}  // namespace adahrs::calib
