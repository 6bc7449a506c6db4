#include "diagnosis/plausible_range.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace adahrs::diagnosis {
namespace {

// A board in a housing lags its air by minutes (physics.md, residual table row 3): an hour is ten
// times beyond that.
constexpr double kMaxDelay_s = 3600.0;
// Self-heating: tens of mW at 100-200 degC/W is a few degC (physics.md row 6); 20 degC is several
// times the largest.
constexpr double kMaxInitialExcess_c = 20.0;
// Scale-factor tempcos: a MEMS gyro's several % over 125 degC is <= 500 ppm/degC, a bridge's TCS
// about 2,100 ppm/degC (physics.md); 1 %/degC is five times the largest. Its curvature: 100
// ppm/degC^2 is 25 % over +-50 degC.
constexpr double kMaxTempco_ppm_per_c = 10000.0;
constexpr double kMaxTempcoCurvature_ppm_per_c2 = 100.0;

}  // namespace

double PlausibleMagnitude(const std::string& component,
                          const std::string& unit,
                          double duration_s) {
  if (component == "delay" && unit == "s")
    return std::min(kMaxDelay_s, duration_s > 0.0 ? duration_s : kMaxDelay_s);
  if (component == "initial_excess" && unit == "degC") return kMaxInitialExcess_c;
  if (unit == "ppm/degC") return kMaxTempco_ppm_per_c;
  if (unit == "ppm/degC^2") return kMaxTempcoCurvature_ppm_per_c2;
  return std::numeric_limits<double>::infinity();
}

std::string NotTestableReason(const std::vector<FindingComponent>& limits, double duration_s) {
  for (const FindingComponent& c : limits) {
    const double max = PlausibleMagnitude(c.name, c.unit, duration_s);
    if (std::abs(c.magnitude) > max || !std::isfinite(c.magnitude)) {
      return fmt::format(
          "not testable here: the smallest {} this recording would find, {:.3g} {}, is beyond "
          "what the effect can physically be (at most {:.4g} {}); the recording gives the term no "
          "leverage",
          c.name,
          std::abs(c.magnitude),
          c.unit,
          max,
          c.unit);
    }
  }
  return "";
}

}  // namespace adahrs::diagnosis
