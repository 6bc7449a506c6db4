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

// A pressure bridge's half loop, pressure or thermal: +-0.05...0.1 % FSO typical, +-0.7 % worst
// (physics.md, the KPY33-R sibling); 1 % of the travel the points visit is beyond every figure.
// Its departure from the fitted polynomial: BFSL nonlinearity +-0.1...0.25 % FSO, +-0.5 % max; 2 %.
constexpr double kMaxHalfLoopOfTravel = 0.01;
constexpr double kMaxDepartureOfTravel = 0.02;

std::string Reason(const FindingComponent& c, double max, const std::string& why) {
  return fmt::format(
      "not testable here: the smallest {} this recording would find, {:.3g} {}, is beyond what "
      "the effect can physically be (at most {:.4g} {}{}); the recording gives the term no "
      "leverage",
      c.name,
      std::abs(c.magnitude),
      c.unit,
      max,
      c.unit,
      why);
}

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
    if (std::abs(c.magnitude) > max || !std::isfinite(c.magnitude)) return Reason(c, max, "");
  }
  return "";
}

std::string NotTestableBridgeReason(const std::vector<FindingComponent>& limits, double travel_pa) {
  for (const FindingComponent& c : limits) {
    const bool loop = c.name == "half_loop";
    const double max = (loop ? kMaxHalfLoopOfTravel : kMaxDepartureOfTravel) * travel_pa;
    if (std::abs(c.magnitude) > max || !std::isfinite(c.magnitude)) {
      return Reason(
          c,
          max,
          fmt::format(
              ", {:.0f} % of the {:.4g} Pa the points travel", (loop ? 1.0 : 2.0), travel_pa));
    }
  }
  return "";
}

}  // namespace adahrs::diagnosis
