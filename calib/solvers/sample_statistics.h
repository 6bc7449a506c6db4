// Mean and standard error of the mean of one step's per-packet samples, the summary every
// reference model consumes. se = s / sqrt(n) with the unbiased sample deviation s; this assumes
// independent samples (true for white noise at the 100 Hz packet rate, optimistic for a drifting
// bias). Throws std::invalid_argument for fewer than two samples or a non-finite sample.
#pragma once

#include <span>
#include <string>

namespace adahrs::calib {

struct SampleMean {
  double mean = 0.0;
  double standard_error = 0.0;
  double standard_deviation = 0.0;
  int count = 0;
};

/// `context` (e.g. "step 4, az1") leads the message of a refusal.
SampleMean SummariseSamples(const std::string& context, std::span<const double> samples);

}  // namespace adahrs::calib
