// A rate-independent hysteresis state that remembers only the last input extreme (a
// "Preisach-lite" operator, shared/physics.md §6 rows 4 and 7): the state is −1 when the input
// has risen far enough since its last reversal, +1 when it has fallen far enough, and moves
// smoothly between the two over an input travel of `span` after each reversal:
//
//   after a reversal at x_ext with state s_ext, moving in direction d = ±1,
//   travel t = min(|x − x_ext| / span, 1),   state = s_ext + (−d − s_ext)·t²·(3 − 2t)
//
// The state is continuous at each reversal and leaves it with zero slope, as a Preisach branch
// does (Rayleigh's law: the hysteretic part grows with the square of the travel); it depends
// only on the sequence of extremes, not on the rate or the step size. A fresh operator starts
// at state 0 (no history). Not modelled: Preisach memory of older extremes (wiping-out and
// exact minor-loop closure); instead a dither of amplitude ±a moves the state by at most
// 6·(2a/span)² per reversal (1e-6 for ±4 Pa of test-set noise on a 20 % FS span of a 15 psi
// sensor). Creep and relaxation with time are not modelled either.
#pragma once

namespace adahrs::sensor_sim {

class LastExtremeHysteresis {
 public:
  /// `span` > 0: input travel after a reversal over which the state fully develops.
  explicit LastExtremeHysteresis(double span) : inv_span_(1.0 / span) {}

  /// Advances to input `x` and returns the state in [−1, 1].
  double Update(double x) {
    if (!started_) {
      started_ = true;
      last_x_ = x;
      extreme_x_ = x;
      return state_;
    }
    if (x == last_x_) return state_;
    const int direction = x > last_x_ ? 1 : -1;
    if (direction != direction_) {
      direction_ = direction;
      extreme_x_ = last_x_;
      extreme_state_ = state_;
    }
    last_x_ = x;
    const double target = -direction;
    const double travel = (x - extreme_x_) * direction * inv_span_;
    if (travel >= 1.0) {
      state_ = target;
    } else {
      state_ = extreme_state_ + (target - extreme_state_) * travel * travel * (3.0 - 2.0 * travel);
    }
    return state_;
  }

  double state() const { return state_; }

 private:
  double inv_span_;
  double last_x_ = 0.0;
  double extreme_x_ = 0.0;
  double extreme_state_ = 0.0;
  double state_ = 0.0;
  int direction_ = 0;
  bool started_ = false;
};

}  // namespace adahrs::sensor_sim
