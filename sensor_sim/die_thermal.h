// Die temperature of one sensor inside a unit, driven by the air around the unit.
//
// Model (a single thermal node, first order):
//   tau_s · dT_die/dt = (T_air + ΔT_self) − T_die
// with ΔT_self = P_dissipated · θ, the steady-state rise of the die above the air from the
// unit's own dissipation (sensor, regulator, dsPIC: physics.md §6 row 6, an E estimate of a few
// °C). Discretised exactly for a piecewise-constant air temperature over each step:
//   T_die ← T_target + (T_die − T_target) · exp(−dt/tau).
// Named effects: `lag` (off: the die follows the air at once) and `self_heating` (off: ΔT_self =
// 0). At power-on the die starts at the air temperature, so self-heating gives the warm-up
// transient. Left out: gradients inside one die, radiation, the housing as a second node (the
// fitted tau lumps housing and board), dependence of tau on chamber air speed or orientation.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

#include "common/param_reader.h"

namespace adahrs::sensor_sim {

struct DieThermalEffects {
  bool lag = true;
  bool self_heating = true;
  static DieThermalEffects Nominal() { return {false, false}; }
  static DieThermalEffects All() { return {true, true}; }
  bool operator==(const DieThermalEffects&) const = default;
};

struct DieThermalParams {
  double tau_s = 300.0;         ///< air → die time constant (E: minutes for a board in a housing)
  double self_heating_c = 3.0;  ///< steady-state die rise above air when powered (E)
  DieThermalEffects effects;

  /// Typical values: tau 300 s, self-heating 3 °C (physics.md §6 rows 3 and 6, E).
  static DieThermalParams Typical();
  /// One sensor's values: tau 300 s ± 50 %, self-heating 3 °C ± 2 °C (E), deterministic per seed.
  static DieThermalParams Draw(uint64_t seed);
  nlohmann::json ToJson() const;
  static DieThermalParams FromJson(const common::ParamReader& reader);
  bool operator==(const DieThermalParams&) const = default;
};

class DieThermal {
 public:
  /// Starts powered-on with the die at `initial_air_temp_c` (no self-heating built up yet).
  DieThermal(const DieThermalParams& params, double step_s, double initial_air_temp_c);

  /// Advances one step with the air at `air_temp_c` over the step; returns the die temperature at
  /// the end of the step. Inline: it runs for every die of every unit every frame.
  double Step(double air_temp_c) {
    const double target_c =
        air_temp_c + (params_.effects.self_heating ? params_.self_heating_c : 0.0);
    die_temp_c_ = target_c + (die_temp_c_ - target_c) * decay_;
    return die_temp_c_;
  }

  /// Holds the air at `air_temp_c` for `duration_s` in one exact step (a soak with no frame).
  void Hold(double air_temp_c, double duration_s);

  double die_temp_c() const { return die_temp_c_; }

 private:
  DieThermalParams params_;
  double decay_;  // exp(−step/tau), or 0 when the lag is off
  double die_temp_c_;
};

}  // namespace adahrs::sensor_sim
