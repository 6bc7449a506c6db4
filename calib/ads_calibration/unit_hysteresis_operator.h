// The calibration's model of a pressure bridge's branch state: the Preisach law the ADS unit runs
// (firmware_model/target/preisach_q15.h, which documents it), in double precision, so that the
// states the calibration fits gains to are the states the unit will compute, without the Q15
// rounding. Law, along a branch that began at input x_b with state s_b, moving in direction
// d = +-1:  s = s_b - 2 d w(min(|x - x_b| / span, 1)),  w(t) = t^2 (3 - 2 t).
// Memory: a reversal pushes a branch start; passing back beyond the previous branch's start
// closes that minor loop and continues the older branch; a fresh operator is virgin at its first
// input x0 (state 0; moving away follows s = -d w(2 |x - x0| / span), rejoined by the oldest
// branch at its mirror point 2 x0 - x_b). Like the unit, it holds kPreisachDepth branch starts
// and forgets the smallest minor loop below the current branch when full.
// Not modelled: anything of a real bridge beyond the unit's law (form and span are assumed).
#pragma once

#include <vector>

namespace adahrs::calib {

class UnitHysteresisOperator {
 public:
  /// `span` > 0: input travel from one saturated state to the other.
  explicit UnitHysteresisOperator(double span);

  /// Advances to `x` and returns the state in [-1, 1] (-1 after a rise, +1 after a fall).
  double Update(double x);

 private:
  struct BranchStart {
    double x;
    double state;
  };
  void Push();
  bool Passed(double x, double start) const { return direction_ > 0 ? x >= start : x <= start; }

  double span_;
  std::vector<BranchStart> starts_;  // oldest first
  double origin_ = 0.0;
  double last_ = 0.0;
  double state_ = 0.0;
  int direction_ = 0;
  bool started_ = false;
};

}  // namespace adahrs::calib
