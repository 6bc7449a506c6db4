// The variance of a linear estimate when the errors wander slowly (docs/diagnose.md "Method").
//
// A candidate whose column changes only between long stretches of the recording (the sense of the
// last temperature change, the time since power-on) is a contrast between stretches minutes or
// hours apart. The jackknife over segments treats segments as independent, so a bias that
// wanders (gyro flicker) reads as such a term. Here the wander is measured from the recording:
// the variogram gamma(tau) = E[(r(t + tau) - r(t))^2] of the residual, over pairs of blocks of
// cells of one run, less what their white noise explains, made non-decreasing in tau; the
// estimate sum_i a_i r_i (a_i its weights in the generalised least squares, summing to 0 within
// each run when the model has an offset) then has the wander variance
//   -1/2 sum_b sum_b' A_b A_b' gamma(|t_b - t_b'|)   (A_b the weights summed over block b),
// plus sum_i a_i^2 v_i of the white part, plus sum_s A_s^2 q_s of an optional independent offset
// per segment (a capture quantiser's bias at each input level).
// Not done: wander across runs (each run's is taken separately), non-stationary wander.
#pragma once

#include <vector>

namespace adahrs::diagnosis {

struct SlowNoiseCell {
  int run = 0;
  int segment = 0;
  double t_s = 0.0;
  double residual = 0.0;   ///< of the model the estimate comes from
  double white_var = 0.0;  ///< variance of the cell's mean from its rows' white noise
  double weight = 0.0;     ///< a_i, the estimate's weight on the cell's value
};

/// Variance of sum_i weight_i y_i (see the header comment); `segment_offset_var` is the variance of
/// an independent offset per segment (0 for none). Cells must be in time order within each
/// segment.
double SlowNoiseVariance(const std::vector<SlowNoiseCell>& cells, double segment_offset_var);

}  // namespace adahrs::diagnosis
