// The calibration sequence language: what a production calibration, burn-in or acceptance run
// does, as an ordered list of steps (shared/reference-method.md "Calibration sequence steps",
// Table 9 of the reference thesis, and its ADS steps of §3.3). A sequence is pure data: it is
// loaded from and saved to JSON (sequence_json.h), refused when invalid (validation.h) and expanded
// into the primitive actions an executor runs (execution_plan.h). Nothing here talks to an
// instrument. Step kinds: accel, gyro, target_temperature, cross_axis, thermal_profile (Watlow F4
// steps), altitude, airspeed, log, prompt. Every step has a one-byte TAG (1…255), stated or
// assigned (EffectiveTags()); consecutive steps never share one.
// Units in every field name (°/s, °C, s, ft, kt CAS); orientation codes as
// rig_sim/fixture_orientation.h (axis made vertical 1 x_B, 2 y_B, 3 z_B; sense 1 up, 2 down).
// Every step kind, field and TAG rule: docs/sequences.md ("Step kinds", "TAGs").
// Not represented: the F4's guaranteed-soak flag per profile step, event outputs and wait-for
// inputs, autostart steps; the executor's interlock thresholds (they belong to the station).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "common/unit_kind.h"
#include "hil/instruments/f4_profile.h"

namespace adahrs::calib {

/// What the batch under test is: decides which step kinds a sequence may hold.
using common::UnitKind;
using common::UnitKindName;

/// The six fixture orientation codes, in the reference's order (reference-method.md §3).
inline constexpr int kOrientationCodes[] = {11, 12, 21, 22, 31, 32};
/// Orientations with x_B, y_B, z_B up: the cross-axis step's three (thesis Eq. 24–29).
inline constexpr int kCrossAxisOrientations[] = {11, 21, 31};

/// True for 11, 12, 21, 22, 31, 32.
bool IsOrientationCode(int code);

struct AccelStep {
  int orientation = 0;
  int64_t packets = 0;
  bool operator==(const AccelStep&) const = default;
};

struct GyroStep {
  int orientation = 0;
  int64_t packets = 0;  ///< acquired at each rate
  double rate_min_dps = 0.0;
  double rate_max_dps = 0.0;
  double rate_increment_dps = 0.0;
  double table_accel_dps2 = 0.0;  ///< angular acceleration of the table between rates
  bool operator==(const GyroStep&) const = default;
};

struct TargetTemperatureStep {
  double target_c = 0.0;
  double band_c = 0.0;  ///< half-width of the band the chamber value must stay inside
  double soak_s = 0.0;  ///< time inside the band before the step ends
  bool operator==(const TargetTemperatureStep&) const = default;
};

struct CrossAxisStep {
  int64_t packets = 0;  ///< acquired at rest and at rate, in each of 11, 21, 31
  double rate_dps = 0.0;
  double table_accel_dps2 = 0.0;
  bool operator==(const CrossAxisStep&) const = default;
};

// The F4 profile step types are the instrument's own data model (hil/instruments/f4_profile.h);
// the sequence language uses them as they are.
using hil::F4End;
using hil::F4EndAction;
using hil::F4Jump;
using hil::F4ProfileStep;
using hil::F4RampRate;
using hil::F4RampTime;
using hil::F4Soak;

struct ThermalProfileStep {
  std::string profile_name;  ///< up to 10 of A–Z, 0–9, space (protocols.md §2.2)
  std::vector<F4ProfileStep> steps;
  bool operator==(const ThermalProfileStep&) const = default;
};

struct AltitudeStep {
  double alt_ft = 0.0;  ///< pressure altitude aim
  double rate_ft_per_min = 0.0;
  bool operator==(const AltitudeStep&) const = default;
};

struct AirspeedStep {
  double cas_kt = 0.0;  ///< calibrated airspeed aim
  double rate_kt_per_min = 0.0;
  bool operator==(const AirspeedStep&) const = default;
};

/// Exactly one of packets and duration_s is set.
struct LogStep {
  std::optional<int64_t> packets;
  std::optional<double> duration_s;
  bool operator==(const LogStep&) const = default;
};

struct PromptStep {
  std::string text;
  bool operator==(const PromptStep&) const = default;
};

using StepBody = std::variant<AccelStep,
                              GyroStep,
                              TargetTemperatureStep,
                              CrossAxisStep,
                              ThermalProfileStep,
                              AltitudeStep,
                              AirspeedStep,
                              LogStep,
                              PromptStep>;

struct Step {
  std::optional<int> tag;  ///< as written in the file; EffectiveTags() gives the one used
  StepBody body;
  bool operator==(const Step&) const = default;
};

struct Sequence {
  static constexpr int kFormatVersion = 1;
  std::string name;
  std::string description;
  UnitKind unit_kind = UnitKind::kImu;
  std::vector<Step> steps;
  bool operator==(const Sequence&) const = default;
};

/// The JSON name of a step kind ("accel", "gyro", ...).
const char* StepKindName(const StepBody& body);
/// The JSON name of an F4 step type ("ramp_time", ...).
const char* F4StepTypeName(const F4ProfileStep& step);
const char* F4EndActionName(F4EndAction action);

/// The equidistant rate commands of a gyro step: rate_min + i·rate_increment for
/// i = 0…round((rate_max − rate_min)/rate_increment). Throws std::invalid_argument when the
/// increment is not positive (validation refuses such steps first).
std::vector<double> GyroRates_dps(const GyroStep& step);

/// The TAG of every step: the explicit one, or the next of the TAGs no step states (ascending,
/// starting over after the last). Throws std::invalid_argument naming the step when a stated TAG
/// is duplicated, none is left to assign, or two consecutive steps would share one; validation
/// reports the same problems as data.
std::vector<uint8_t> EffectiveTags(const Sequence& sequence);

}  // namespace adahrs::calib
