// A rate-independent hysteresis state with Preisach's memory rules (shared/physics.md §6 rows 4
// and 7): the state is −1 when the input has risen far enough, +1 when it has fallen far enough,
// and in between it is set by the extremes the input has visited that are not wiped out. Along a
// branch from a reversal x_b at state s_b in direction d = ±1: s(x) = s_b − 2·d·F(|x − x_b| /
// span), F(t) = t²(3 − 2t) for t < 1, 1 beyond (Rayleigh's law at the reversal). Minor loops close
// exactly; passing back beyond the previous branch's start wipes the loop out (return-point
// memory), so noise reversals on a slow ramp are harmless. A fresh operator starts demagnetised
// (state 0) at its first input and follows the virgin curve.
// Units: the input's (Pa or °C, with span in the same unit); state dimensionless in [−1, 1].
// Law, virgin curve and why these rules: docs/models/pressure-bridge.md ("Equations",
// Hysteresis).
// Left out: nesting deeper than kMaxBranches (the smallest minor loop is forgotten), creep and
// relaxation with time, an Everett function that depends on where the loop lies.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace adahrs::sensor_sim {

class PreisachHysteresis {
 public:
  static constexpr std::size_t kMaxBranches = 64;

  /// `span` > 0: travel from one saturated state to the other along a branch.
  explicit PreisachHysteresis(double span) : inv_span_(1.0 / span) {}

  /// Advances to input `x` and returns the state in [−1, 1].
  double Update(double x) {
    if (!started_) {
      started_ = true;
      origin_x_ = x;
      last_x_ = x;
      return state_;
    }
    if (x == last_x_) return state_;
    const int direction = x > last_x_ ? 1 : -1;
    if (direction_ != 0 && direction != direction_) Push(Branch{last_x_, state_});
    direction_ = direction;
    last_x_ = x;
    // Wiping-out: beyond the previous branch's start, the loop between them is closed.
    while (size_ >= 2 && (x - branches_[size_ - 2].start_x) * direction >= 0.0) size_ -= 2;
    // The oldest reversal's previous extreme is the virgin history's mirror point.
    if (size_ == 1 && (x - (2.0 * origin_x_ - branches_[0].start_x)) * direction >= 0.0) size_ = 0;
    if (size_ == 0) {
      const double u = std::abs(x - origin_x_);
      state_ = -(x > origin_x_ ? 1.0 : -1.0) * Weight(2.0 * u * inv_span_);
    } else {
      const Branch& b = branches_[size_ - 1];
      state_ = b.start_state - 2.0 * direction * Weight(std::abs(x - b.start_x) * inv_span_);
    }
    state_ = std::clamp(state_, -1.0, 1.0);
    return state_;
  }

  double state() const { return state_; }

 private:
  struct Branch {
    double start_x;
    double start_state;
  };

  // The branch weight F(t) (t = travel / span, >= 0).
  static double Weight(double t) { return t >= 1.0 ? 1.0 : t * t * (3.0 - 2.0 * t); }

  // When full, the smallest minor loop below the current branch is forgotten: the pair of
  // consecutive starts closest in input, as if the excursion between them had not happened (the
  // directions still alternate); a major branch's start is far from its neighbours and stays.
  void Push(const Branch& b) {
    if (size_ == kMaxBranches) {
      std::size_t smallest = 0;
      for (std::size_t i = 1; i + 2 < kMaxBranches; ++i) {
        if (std::abs(branches_[i + 1].start_x - branches_[i].start_x) <
            std::abs(branches_[smallest + 1].start_x - branches_[smallest].start_x)) {
          smallest = i;
        }
      }
      std::copy(branches_ + smallest + 2, branches_ + kMaxBranches, branches_ + smallest);
      size_ -= 2;
    }
    branches_[size_++] = b;
  }

  double inv_span_;
  Branch branches_[kMaxBranches] = {};
  std::size_t size_ = 0;
  double origin_x_ = 0.0;
  double last_x_ = 0.0;
  double state_ = 0.0;
  int direction_ = 0;
  bool started_ = false;
};

}  // namespace adahrs::sensor_sim
