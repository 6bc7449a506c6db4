#include "calib/ads_calibration/unit_hysteresis_operator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "firmware_model/unit_firmware.h"

namespace adahrs::calib {
namespace {

double Smoothstep(double t) {
  const double u = std::min(t, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

}  // namespace

UnitHysteresisOperator::UnitHysteresisOperator(double span) : span_(span) {
  if (!(span > 0.0))
    throw std::invalid_argument("hysteresis operator: span " + std::to_string(span) +
                                " must be positive");
}

void UnitHysteresisOperator::Push() {
  if (starts_.size() == firmware_model::kPreisachDepth) {
    size_t smallest = 0;
    for (size_t i = 1; i + 2 < starts_.size(); ++i) {
      if (std::abs(starts_[i + 1].x - starts_[i].x) <
          std::abs(starts_[smallest + 1].x - starts_[smallest].x)) {
        smallest = i;
      }
    }
    starts_.erase(starts_.begin() + static_cast<long>(smallest),
                  starts_.begin() + static_cast<long>(smallest) + 2);
  }
  starts_.push_back({last_, state_});
}

double UnitHysteresisOperator::Update(double x) {
  if (!started_) {
    started_ = true;
    origin_ = last_ = x;
    return state_;
  }
  if (x == last_) return state_;
  const int direction = x > last_ ? 1 : -1;
  if (direction_ != 0 && direction != direction_) Push();
  direction_ = direction;
  last_ = x;
  while (starts_.size() >= 2 && Passed(x, starts_[starts_.size() - 2].x))
    starts_.resize(starts_.size() - 2);
  if (starts_.size() == 1 && Passed(x, 2.0 * origin_ - starts_[0].x)) starts_.clear();
  if (starts_.empty()) {
    state_ = -(x > origin_ ? 1.0 : -1.0) * Smoothstep(2.0 * std::abs(x - origin_) / span_);
  } else {
    const BranchStart& b = starts_.back();
    state_ =
        std::clamp(b.state - 2.0 * direction * Smoothstep(std::abs(x - b.x) / span_), -1.0, 1.0);
  }
  return state_;
}

}  // namespace adahrs::calib
