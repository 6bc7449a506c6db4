#include "proving/studies/study_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace adahrs::proving {

using nlohmann::json;

json ErrorDistribution::ToJson() const {
  return {{"count", count},
          {"mean", mean},
          {"p50", p50},
          {"p90", p90},
          {"p95", p95},
          {"p99", p99},
          {"max", max}};
}

json PairedInterval::ToJson() const {
  return {{"units", units}, {"mean", mean}, {"ci95_low", ci95_low}, {"ci95_high", ci95_high}};
}

ErrorDistribution StudyDistribution(std::vector<double> values) {
  std::erase_if(values, [](double v) { return !std::isfinite(v); });
  ErrorDistribution d;
  d.count = static_cast<int>(values.size());
  if (values.empty()) {
    d.mean = d.p50 = d.p90 = d.p95 = d.p99 = d.max = std::numeric_limits<double>::quiet_NaN();
    return d;
  }
  std::sort(values.begin(), values.end());
  auto rank = [&](double p) {
    const auto k = static_cast<size_t>(std::ceil(p * static_cast<double>(values.size())));
    return values[std::max<size_t>(k, 1) - 1];
  };
  double sum = 0.0;
  for (double v : values) sum += v;
  d.mean = sum / static_cast<double>(values.size());
  d.p50 = rank(0.50);
  d.p90 = rank(0.90);
  d.p95 = rank(0.95);
  d.p99 = rank(0.99);
  d.max = values.back();
  return d;
}

PairedInterval StudyBootstrap(const std::vector<double>& diffs, uint64_t seed) {
  PairedInterval p;
  p.units = static_cast<int>(diffs.size());
  if (diffs.empty()) {
    p.mean = p.ci95_low = p.ci95_high = std::numeric_limits<double>::quiet_NaN();
    return p;
  }
  double sum = 0.0;
  for (double d : diffs) sum += d;
  p.mean = sum / static_cast<double>(diffs.size());
  std::mt19937_64 rng(seed);
  std::vector<double> means(kStudyBootstrapResamples);
  for (double& m : means) {
    double s = 0.0;
    for (size_t i = 0; i < diffs.size(); ++i) s += diffs[rng() % diffs.size()];
    m = s / static_cast<double>(diffs.size());
  }
  std::sort(means.begin(), means.end());
  p.ci95_low = means[static_cast<size_t>(0.025 * kStudyBootstrapResamples)];
  p.ci95_high = means[static_cast<size_t>(0.975 * kStudyBootstrapResamples) - 1];
  return p;
}

StrategyTally TallyStrategy(const std::vector<StudyUnitResult>& results,
                            size_t s,
                            const std::vector<OutcomePass>& criteria,
                            const std::vector<OutcomeError>& errors) {
  StrategyTally t;
  t.units = static_cast<int>(results.size());
  std::vector<int> passed(criteria.size(), 0);
  std::vector<std::vector<double>> values(errors.size());
  for (const StudyUnitResult& r : results) {
    const StrategyOutcome& o = r.outcomes.at(s);
    t.fitted += o.fitted;
    for (size_t c = 0; c < criteria.size(); ++c) passed[c] += criteria[c](o);
    for (size_t e = 0; e < errors.size(); ++e) values[e].push_back(errors[e](o));
  }
  const double n = std::max<double>(1.0, static_cast<double>(results.size()));
  for (int p : passed) t.yields.push_back(p / n);
  for (std::vector<double>& v : values) t.errors.push_back(StudyDistribution(std::move(v)));
  return t;
}

std::vector<PairedInterval> PairedIntervals(const std::vector<StudyUnitResult>& results,
                                            uint64_t seed,
                                            const std::vector<OutcomePass>& criteria,
                                            const std::vector<OutcomeError>& errors) {
  std::vector<std::vector<double>> diffs(criteria.size() + errors.size());
  for (const StudyUnitResult& r : results) {
    const StrategyOutcome& a = r.outcomes[0];
    const StrategyOutcome& b = r.outcomes[1];
    for (size_t c = 0; c < criteria.size(); ++c) {
      diffs[c].push_back(static_cast<double>(criteria[c](b)) - static_cast<double>(criteria[c](a)));
    }
    if (!(a.fitted && b.fitted)) continue;
    for (size_t e = 0; e < errors.size(); ++e)
      diffs[criteria.size() + e].push_back(errors[e](b) - errors[e](a));
  }
  std::vector<PairedInterval> intervals;
  for (size_t i = 0; i < diffs.size(); ++i) intervals.push_back(StudyBootstrap(diffs[i], seed + i));
  return intervals;
}

}  // namespace adahrs::proving
