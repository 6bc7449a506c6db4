// A second hysteresis law for the pressure bridges, of another family than preisach_hysteresis.h
// (a truth variant: the calibration's operator follows the travel law, so a unit on this law
// tests a pipeline whose hysteresis model does not have the truth's form).
//
// Law: a generalised Prandtl-Ishlinskii model (K. Kuhnen, "Modeling, identification and
// compensation of complex hysteretic nonlinearities: a modified Prandtl-Ishlinskii approach",
// European Journal of Control 9, 2003): kOperators play operators of radius
// r_i = (span / 2) i / kOperators, each p_i <- clamp(p_i, x - r_i, x + r_i), read as
// h_i = (p_i - x) / r_i in [-1, 1] (-1 after a rise of 2 r_i, +1 after a fall: the bridges'
// convention), weighted w_i ~ exp(-r_i / (0.15 span)) (sum 1), and scaled by an envelope that
// grows across the input's working range [low, high]:
//   s = clamp(g(x) sum_i w_i h_i, -1, 1),   g(x) = 1 + kEnvelopeSlope (x - centre) / half_range.
// Against the travel law: a branch leaves its reversal with a finite slope (sum w_i / r_i) where
// the travel law leaves it with zero slope; it is concave all the way to saturation at a travel
// of `span`; and the same excursion makes a loop 1.6 / 0.4 = 4 times larger at the top of the
// range than at the bottom, where the travel law's loops depend on the travel alone. The weights
// and the envelope are engineering estimates chosen to differ from the travel law, not fitted
// to a part (docs/sensor-models.md).
// A fresh operator starts at its first input x0 with every p_i = x0: state 0.
// Wiping-out and exact minor-loop closure hold (each play operator has them).
// Not modelled: creep, rate dependence.
#pragma once

#include <array>

namespace adahrs::sensor_sim {

class PlayHysteresis {
 public:
  static constexpr int kOperators = 16;
  static constexpr double kEnvelopeSlope = 0.6;

  /// `span` > 0: travel to saturation; `low` < `high`: the input's working range (the envelope's).
  PlayHysteresis(double span, double low, double high);

  /// Advances to input `x` and returns the state in [-1, 1].
  double Update(double x);

  double state() const { return state_; }

 private:
  std::array<double, kOperators> radius_{};
  std::array<double, kOperators> weight_{};
  std::array<double, kOperators> play_{};
  double centre_ = 0.0, inv_half_range_ = 0.0;
  double state_ = 0.0;
  bool started_ = false;
};

}  // namespace adahrs::sensor_sim
