#include "calib/solvers/sample_statistics.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace adahrs::calib {

SampleMean SummariseSamples(const std::string& context, std::span<const double> samples) {
  if (samples.size() < 2) {
    throw std::invalid_argument(fmt::format(
        "{}: {} sample(s), at least 2 are needed for a standard error", context, samples.size()));
  }
  // Two passes: the mean first, then deviations from it (no cancellation for large offsets such
  // as gyro counts ~4e6).
  double sum = 0.0;
  for (size_t i = 0; i < samples.size(); ++i) {
    if (!std::isfinite(samples[i])) {
      throw std::invalid_argument(fmt::format("{}: sample {} is not finite", context, i));
    }
    sum += samples[i];
  }
  SampleMean out;
  out.count = static_cast<int>(samples.size());
  out.mean = sum / out.count;
  double ss = 0.0;
  for (double v : samples) ss += (v - out.mean) * (v - out.mean);
  out.standard_deviation = std::sqrt(ss / (out.count - 1));
  out.standard_error = out.standard_deviation / std::sqrt(static_cast<double>(out.count));
  return out;
}

}  // namespace adahrs::calib
