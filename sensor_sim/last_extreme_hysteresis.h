// A rate-independent hysteresis state with return-point memory (a "Preisach-lite" operator,
// shared/physics.md §6 rows 4 and 7): the state is −1 when the input has risen far enough since
// the branch began, +1 when it has fallen far enough, and moves smoothly between the two over an
// input travel of `span` along each branch:
//
//   on a branch that began at x_b with state s_b, moving in direction d = ±1,
//   travel t = min(|x − x_b| / span, 1),   state = s_b + (−d − s_b)·t²·(3 − 2t)
//
// A reversal begins a new branch at the reversal point (the state is continuous there and leaves
// it with zero slope, as a Preisach branch does: Rayleigh's law, the hysteretic part grows with
// the square of the travel). Return-point memory (Preisach's wiping-out property): when the input
// passes back to or beyond the point where the previous branch began, the minor loop between them is
// closed and forgotten, and the state continues the older branch as if the excursion had never
// happened. Without it, input noise during a slow ramp would restart the smoothstep at every
// noise reversal and the state would develop far more slowly than along a clean ramp: a noisy
// and a clean path with the same extremes beyond the noise would leave different states. The
// state depends only on the sequence of extremes that are not wiped out, not on the rate or the
// step size. A fresh operator starts at state 0 (no history).
// Not modelled: exact minor-loop closure (a closing minor loop may leave a jump of at most
// 6·(2a/span)² for a loop of amplitude a, 1e-6 for ±4 Pa of test-set noise on a 20 % FS span of a
// 15 psi sensor); nesting deeper than kMaxBranches (the smallest minor loop is then forgotten);
// creep and relaxation with time.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace adahrs::sensor_sim {

class LastExtremeHysteresis {
 public:
  static constexpr std::size_t kMaxBranches = 64;

  /// `span` > 0: input travel after a reversal over which the state fully develops.
  explicit LastExtremeHysteresis(double span) : inv_span_(1.0 / span) {}

  /// Advances to input `x` and returns the state in [−1, 1].
  double Update(double x) {
    if (!started_) {
      started_ = true;
      last_x_ = x;
      return state_;
    }
    if (x == last_x_) return state_;
    const int direction = x > last_x_ ? 1 : -1;
    if (direction != direction_) {
      Push(Branch{last_x_, state_});
      direction_ = direction;
    }
    last_x_ = x;
    // Return-point memory: beyond the previous branch's start, the minor loop is closed.
    while (size_ >= 3 && (x - branches_[size_ - 2].start_x) * direction >= 0.0) size_ -= 2;
    const Branch& b = branches_[size_ - 1];
    const double travel = std::min(std::abs(x - b.start_x) * inv_span_, 1.0);
    const double target = -direction;
    state_ = b.start_state + (target - b.start_state) * travel * travel * (3.0 - 2.0 * travel);
    return state_;
  }

  double state() const { return state_; }

 private:
  struct Branch {
    double start_x;
    double start_state;
  };

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
  double last_x_ = 0.0;
  double state_ = 0.0;
  int direction_ = 0;
  bool started_ = false;
};

}  // namespace adahrs::sensor_sim
