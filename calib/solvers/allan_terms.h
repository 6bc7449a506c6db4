// The noise terms of a record taken at rest, read off its overlapping Allan deviation (IEEE Std
// 952-1997 Annex C; the estimator and its conventions are common/allan.h): the white term at
// tau = 1 s (IEEE 952's random-walk coefficient N and the datasheets' one-sided density sqrt(2) N)
// and the bias instability B = sigma_min / 0.664 with the tau it was read at, flagged when the
// record is too short to reach 1 s or to show the floor.
// Units: those of the samples (the caller names them); tau in s.
// Derivation: docs/calibration-solvers.md ("Models", Allan terms).
// Left out: rate random walk, rate ramp and quantisation terms, confidence intervals beyond each
// curve point's relative error.
#pragma once

#include <vector>

#include "common/allan.h"

namespace adahrs::calib {

struct AllanTerms {
  std::vector<common::AllanPoint> curve;    ///< about 10 points per decade, m = 1 ... N/10
  double record_s = 0.0;                    ///< N * dt
  double white_tau_s = 0.0;                 ///< tau at which the white term was read
  double random_walk_per_rts = 0.0;         ///< N_952, unit/sqrt(s)
  double density_one_sided_per_rthz = 0.0;  ///< sqrt(2) * N_952, unit/sqrt(Hz)
  double bias_instability = 0.0;            ///< sigma_min / 0.664, unit
  double bias_instability_tau_s = 0.0;      ///< tau of sigma_min
  bool minimum_at_longest_tau = false;      ///< the floor is not reached: B is an upper bound
};

/// The terms of `samples` (averages over consecutive `dt_s` intervals, e.g. one per packet).
/// Throws std::invalid_argument if there are fewer than 20 samples or dt_s is not positive.
AllanTerms ReadAllanTerms(const std::vector<double>& samples, double dt_s);

}  // namespace adahrs::calib
