// A Watlow F4 ramping profile as the controller stores it (protocols.md §2.4, DRV; Watlow F4
// User's Manual ch. 5): up to 256 steps of five types — ramp by time, ramp by rate, soak, jump,
// end. The sequence language (calib/sequence/sequence.h) writes thermal_profile steps in these
// terms and the chamber driver downloads them register by register.
// Not represented: guaranteed-soak bands, event outputs, wait-for inputs, autostart steps.
#pragma once

#include <variant>

namespace adahrs::hil {

/// Ramp from the current set point to target_c in duration_s (F4 step type 1).
struct F4RampTime {
  double target_c = 0.0;
  double duration_s = 0.0;
  bool operator==(const F4RampTime&) const = default;
};
/// Ramp from the current set point to target_c at rate_c_per_min (F4 step type 2).
struct F4RampRate {
  double target_c = 0.0;
  double rate_c_per_min = 0.0;
  bool operator==(const F4RampRate&) const = default;
};
/// Hold the current set point for duration_s (F4 step type 3).
struct F4Soak {
  double duration_s = 0.0;
  bool operator==(const F4Soak&) const = default;
};
/// Go back to profile step to_step (1-based) `count` more times, then go on (F4 step type 4).
struct F4Jump {
  int to_step = 0;
  int count = 0;
  bool operator==(const F4Jump&) const = default;
};
/// What the chamber does after the profile (F4 step type 5, register 4060).
enum class F4EndAction { kHold, kControlOff, kAllOff, kIdle };
struct F4End {
  F4EndAction action = F4EndAction::kHold;
  double idle_c = 0.0;  ///< set point after the profile, for kIdle only
  bool operator==(const F4End&) const = default;
};
using F4ProfileStep = std::variant<F4RampTime, F4RampRate, F4Soak, F4Jump, F4End>;

}  // namespace adahrs::hil
