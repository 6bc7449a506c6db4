#include "calib/report/nice_ticks.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace adahrs::calib {
namespace {

// The smallest 1, 2 or 5 x 10^k that is >= `raw`.
double NiceStepAtLeast(double raw) {
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double mantissa : {1.0, 2.0, 5.0, 10.0}) {
    if (mantissa * power >= raw * (1.0 - 1e-12)) return mantissa * power;
  }
  return 10.0 * power;
}

}  // namespace

AxisTicks NiceTicks(double min, double max, int max_ticks) {
  if (!std::isfinite(min) || !std::isfinite(max) || max_ticks < 2) {
    throw std::invalid_argument(fmt::format(
        "NiceTicks: range [{}, {}] with {} ticks is not drawable", min, max, max_ticks));
  }
  if (min > max) std::swap(min, max);
  if (max - min <= 1e-12 * std::max(1.0, std::abs(max))) {
    const double half = std::max(0.5, std::abs(min) * 0.01);
    min -= half;
    max += half;
  }
  AxisTicks ticks;
  ticks.step = NiceStepAtLeast((max - min) / (max_ticks - 1));
  while (true) {
    ticks.lo = std::floor(min / ticks.step + 1e-9) * ticks.step;
    ticks.hi = std::ceil(max / ticks.step - 1e-9) * ticks.step;
    if (std::lround((ticks.hi - ticks.lo) / ticks.step) + 1 <= max_ticks) break;
    ticks.step = NiceStepAtLeast(ticks.step * 1.000001);
  }
  const long count = std::lround((ticks.hi - ticks.lo) / ticks.step) + 1;
  for (long i = 0; i < count; ++i) {
    const double value = ticks.lo + static_cast<double>(i) * ticks.step;
    ticks.values.push_back(std::abs(value) < 1e-9 * ticks.step ? 0.0 : value);
  }
  return ticks;
}

AxisTicks DecadeTicks(double log10_min, double log10_max) {
  if (!std::isfinite(log10_min) || !std::isfinite(log10_max)) {
    throw std::invalid_argument(
        fmt::format("DecadeTicks: range 10^[{}, {}] is not drawable", log10_min, log10_max));
  }
  if (log10_min > log10_max) std::swap(log10_min, log10_max);
  AxisTicks ticks;
  ticks.step = 1.0;
  ticks.lo = std::floor(log10_min + 1e-9);
  ticks.hi = std::max(ticks.lo + 1.0, std::ceil(log10_max - 1e-9));
  for (double e = ticks.lo; e <= ticks.hi + 0.5; e += 1.0) ticks.values.push_back(e);
  return ticks;
}

std::string DecadeLabel(double exponent) { return fmt::format("{:g}", std::pow(10.0, exponent)); }

std::string TickLabel(double value, double step) {
  const double digits = -std::floor(std::log10(step) + 1e-9);
  if (step < 1e-4 || step >= 1e6) return fmt::format("{:g}", value);
  return fmt::format("{:.{}f}", value, static_cast<int>(std::max(0.0, digits)));
}

}  // namespace adahrs::calib
