#include "calib/solvers/allan_terms.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace adahrs::calib {
namespace {

constexpr size_t kMinSamples = 20;
constexpr double kWhiteReadTau_s = 1.0;
// IEEE 952 C.2: the Allan deviation of a flicker (1/f) rate noise levels off at 0.664 B.
constexpr double kFlickerFloorRatio = 0.664;

}  // namespace

AllanTerms ReadAllanTerms(const std::vector<double>& samples, double dt_s) {
  if (samples.size() < kMinSamples || !(dt_s > 0.0)) {
    throw std::invalid_argument("Allan terms need at least " + std::to_string(kMinSamples) +
                                " samples at a positive interval, got " +
                                std::to_string(samples.size()) + " at " + std::to_string(dt_s) +
                                " s");
  }
  AllanTerms t;
  t.curve = common::OverlappingAllanDeviation(samples, dt_s);
  t.record_s = static_cast<double>(samples.size()) * dt_s;

  // White term: log-log interpolation between the points around 1 s (the slope there is -1/2 for
  // white noise, so sigma * sqrt(tau) is the same from either point), else the longest tau.
  const std::vector<common::AllanPoint>& c = t.curve;
  t.white_tau_s = c.back().tau_s;
  double sigma_at_white = c.back().adev;
  for (size_t i = 0; i + 1 < c.size(); ++i) {
    if (c[i].tau_s <= kWhiteReadTau_s && kWhiteReadTau_s <= c[i + 1].tau_s) {
      const double f =
          std::log(kWhiteReadTau_s / c[i].tau_s) / std::log(c[i + 1].tau_s / c[i].tau_s);
      sigma_at_white = std::exp(std::log(c[i].adev) + f * std::log(c[i + 1].adev / c[i].adev));
      t.white_tau_s = kWhiteReadTau_s;
      break;
    }
  }
  t.random_walk_per_rts = sigma_at_white * std::sqrt(t.white_tau_s);
  t.density_one_sided_per_rthz = std::sqrt(2.0) * t.random_walk_per_rts;

  size_t lowest = 0;
  for (size_t i = 1; i < c.size(); ++i) {
    if (c[i].adev < c[lowest].adev) lowest = i;
  }
  t.bias_instability = c[lowest].adev / kFlickerFloorRatio;
  t.bias_instability_tau_s = c[lowest].tau_s;
  t.minimum_at_longest_tau = lowest + 1 == c.size();
  return t;
}

}  // namespace adahrs::calib
