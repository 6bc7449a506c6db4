// A second hysteresis law for the pressure bridges, of another family than preisach_hysteresis.h
// (a truth variant: the calibration's operator follows the travel law, so a unit on this law tests
// a pipeline whose hysteresis model does not have the truth's form). A generalised
// Prandtl-Ishlinskii model (K. Kuhnen, European Journal of Control 9, 2003): kOperators play
// operators of radii up to span / 2, weights falling with radius, scaled by an envelope that grows
// across the input's working range; unlike the travel law a branch leaves its reversal with a
// finite slope and loop size depends on where the loop lies. Starts at state 0.
// Units: the input's (Pa or °C); state dimensionless in [−1, 1], −1 after a rise.
// Law, weights, envelope (engineering estimates, not fitted to a part): docs/sensor-models.md
// ("Truth variants (model form)", the play-operator law).
// Left out: creep, rate dependence.
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
