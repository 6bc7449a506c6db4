// The statistics a study summary is made of, for IMU and ADS studies alike: per strategy the
// fraction of units passing each criterion and the distribution of each worst error (percentiles
// by nearest rank over the finite values: units whose fit failed are left out); between two
// strategies the mean paired difference second − first with its percentile-bootstrap 95 %
// interval (units resampled with replacement, kStudyBootstrapResamples, a fixed seed each).
// What the criteria and errors are is the caller's: functions of a StrategyOutcome.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "proving/studies/imu_study.h"

namespace adahrs::proving {

inline constexpr int kStudyBootstrapResamples = 2000;

struct ErrorDistribution {
  int count = 0;
  double mean = 0.0, p50 = 0.0, p90 = 0.0, p95 = 0.0, p99 = 0.0, max = 0.0;
  nlohmann::json ToJson() const;
};

/// The mean of a paired difference with its bootstrap 95 % interval (percentile method).
struct PairedInterval {
  int units = 0;
  double mean = 0.0, ci95_low = 0.0, ci95_high = 0.0;
  nlohmann::json ToJson() const;
};

using OutcomePass = bool (*)(const StrategyOutcome&);
using OutcomeError = double (*)(const StrategyOutcome&);

/// Strategy `s` over every unit: units fitted, the fraction passing each of `criteria` and the
/// distribution of each of `errors`, in their order.
struct StrategyTally {
  int units = 0;
  int fitted = 0;
  std::vector<double> yields;
  std::vector<ErrorDistribution> errors;
};
StrategyTally TallyStrategy(const std::vector<StudyUnitResult>& results,
                            size_t s,
                            const std::vector<OutcomePass>& criteria,
                            const std::vector<OutcomeError>& errors);

/// Second − first (outcomes 1 and 0) of each of `criteria` (pass 1/0, every unit), then of each
/// of `errors` (the units both fitted); interval i is bootstrapped with `seed` + i.
std::vector<PairedInterval> PairedIntervals(const std::vector<StudyUnitResult>& results,
                                            uint64_t seed,
                                            const std::vector<OutcomePass>& criteria,
                                            const std::vector<OutcomeError>& errors);

/// The distribution of the finite `values` by nearest rank.
ErrorDistribution StudyDistribution(std::vector<double> values);
/// The mean of `diffs` with its percentile bootstrap interval (kStudyBootstrapResamples, `seed`).
PairedInterval StudyBootstrap(const std::vector<double>& diffs, uint64_t seed);

}  // namespace adahrs::proving
