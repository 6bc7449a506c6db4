#include "calib/sequence/sequence.h"

#include "common/overloaded.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace adahrs::calib {

using common::Overloaded;

bool IsOrientationCode(int code) {
  return std::find(std::begin(kOrientationCodes), std::end(kOrientationCodes), code) !=
         std::end(kOrientationCodes);
}

const char* StepKindName(const StepBody& body) {
  return std::visit(Overloaded{
                        [](const AccelStep&) { return "accel"; },
                        [](const GyroStep&) { return "gyro"; },
                        [](const TargetTemperatureStep&) { return "target_temperature"; },
                        [](const CrossAxisStep&) { return "cross_axis"; },
                        [](const ThermalProfileStep&) { return "thermal_profile"; },
                        [](const AltitudeStep&) { return "altitude"; },
                        [](const AirspeedStep&) { return "airspeed"; },
                        [](const LogStep&) { return "log"; },
                        [](const PromptStep&) { return "prompt"; },
                    },
                    body);
}

const char* F4StepTypeName(const F4ProfileStep& step) {
  return std::visit(Overloaded{
                        [](const F4RampTime&) { return "ramp_time"; },
                        [](const F4RampRate&) { return "ramp_rate"; },
                        [](const F4Soak&) { return "soak"; },
                        [](const F4Jump&) { return "jump"; },
                        [](const F4End&) { return "end"; },
                    },
                    step);
}

const char* F4EndActionName(F4EndAction action) {
  switch (action) {
    case F4EndAction::kHold:
      return "hold";
    case F4EndAction::kControlOff:
      return "control_off";
    case F4EndAction::kAllOff:
      return "all_off";
    case F4EndAction::kIdle:
      return "idle";
  }
  return "hold";
}

std::vector<double> GyroRates_dps(const GyroStep& step) {
  if (!(step.rate_increment_dps > 0.0)) {
    throw std::invalid_argument("gyro step: rate_increment_dps must be positive, got " +
                                std::to_string(step.rate_increment_dps));
  }
  // Each rate is computed from rate_min, not accumulated, so −150 + 6·50 is exactly 150.
  const long count =
      std::lround((step.rate_max_dps - step.rate_min_dps) / step.rate_increment_dps) + 1;
  std::vector<double> rates_dps;
  for (long i = 0; i < count; ++i) {
    rates_dps.push_back(step.rate_min_dps + static_cast<double>(i) * step.rate_increment_dps);
  }
  return rates_dps;
}

std::vector<uint8_t> EffectiveTags(const Sequence& sequence) {
  constexpr int kMaxTag = 255;
  std::vector<bool> used(kMaxTag + 1, false);
  for (size_t i = 0; i < sequence.steps.size(); ++i) {
    const std::optional<int>& tag = sequence.steps[i].tag;
    if (!tag) continue;
    if (*tag < 1 || *tag > kMaxTag) {
      throw std::invalid_argument("step " + std::to_string(i) + ": tag " + std::to_string(*tag) +
                                  " outside 1…255");
    }
    if (used[static_cast<size_t>(*tag)]) {
      throw std::invalid_argument("step " + std::to_string(i) + ": tag " + std::to_string(*tag) +
                                  " already used by an earlier step");
    }
    used[static_cast<size_t>(*tag)] = true;
  }
  std::vector<int> free_tags;  // the TAGs no step states, taken in turn and reused cyclically
  for (int t = 1; t <= kMaxTag; ++t) {
    if (!used[static_cast<size_t>(t)]) free_tags.push_back(t);
  }
  std::vector<uint8_t> tags;
  size_t next = 0;
  for (size_t i = 0; i < sequence.steps.size(); ++i) {
    const std::optional<int>& tag = sequence.steps[i].tag;
    if (tag) {
      tags.push_back(static_cast<uint8_t>(*tag));
      continue;
    }
    if (free_tags.empty()) {
      throw std::invalid_argument("step " + std::to_string(i) + ": no TAG left in 1…255 to assign");
    }
    const int t = free_tags[next++ % free_tags.size()];
    if (!tags.empty() && tags.back() == t) {
      throw std::invalid_argument("step " + std::to_string(i) + ": TAG " + std::to_string(t) +
                                  " would follow itself (one TAG left in 1…255 for " +
                                  "consecutive steps)");
    }
    tags.push_back(static_cast<uint8_t>(t));
  }
  return tags;
}

}  // namespace adahrs::calib
