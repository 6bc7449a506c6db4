// The expansion of a valid sequence into the primitive actions an executor runs, in order, each
// with the step and TAG it belongs to and a duration estimate (PlanTiming: table ramps, chamber
// moves at the station's declared heating and cooling rates and soaks, F4 profile loops, ADTS
// slews and its 15 s to "stable", N / packet rate). Pure data: no instrument is touched, and the
// executor still waits on real conditions, never on these estimates, which only feed the plan's
// ETA. A command is estimated at 0 s and the wait after it carries the motion.
// Units: seconds; rates in deg/s, deg/s^2, degC/min, ft/min, kt/min as the fields name them.
// The expansion of each step kind and the duration model: docs/sequences.md ("Expansion").
// Not modelled: instrument command latency, packet loss, interlock retries, operator delays
// beyond the fixed prompt time, a chamber's slower first-order approach in the last degrees
// before a set point.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "calib/sequence/sequence.h"
#include "calib/sequence/sequence_limits.h"

namespace adahrs::calib {

struct PromptOperator {
  std::string text;
};
/// Mount the batch in a fixture orientation (an operator action; the virtual fixture in
/// simulated runs).
struct MountOrientation {
  int orientation = 0;
};
/// Interlock: the measured gravity vector must match the orientation before acquiring.
struct CheckGravity {
  int orientation = 0;
};
/// Interlock: jog the table at jog_rate_dps and check the gyro axis that sees it.
struct CheckGyroAxis {
  int orientation = 0;
  double jog_rate_dps = 0.0;
};
struct SetTableRate {
  double rate_dps = 0.0;
  double accel_dps2 = 0.0;
};
struct WaitTableAtRate {
  double rate_dps = 0.0;
};
struct StopTable {
  double accel_dps2 = 0.0;
};
struct SetChamberSetPoint {
  double temp_c = 0.0;
};
struct WaitChamberSoak {
  double temp_c = 0.0;
  double band_c = 0.0;
  double soak_s = 0.0;
};
struct DownloadProfile {
  ThermalProfileStep profile;
};
/// Start the downloaded profile and log every packet until the controller reports its end.
struct RunProfileLogging {
  std::string profile_name;
};
struct SetAltitude {
  double alt_ft = 0.0;
  double rate_ft_per_min = 0.0;
};
struct SetAirspeed {
  double cas_kt = 0.0;
  double rate_kt_per_min = 0.0;
};
struct WaitAdtsStable {};
struct AcquirePackets {
  int64_t packets = 0;
};
struct LogForDuration {
  double duration_s = 0.0;
};

using Action = std::variant<PromptOperator,
                            MountOrientation,
                            CheckGravity,
                            CheckGyroAxis,
                            SetTableRate,
                            WaitTableAtRate,
                            StopTable,
                            SetChamberSetPoint,
                            WaitChamberSoak,
                            DownloadProfile,
                            RunProfileLogging,
                            SetAltitude,
                            SetAirspeed,
                            WaitAdtsStable,
                            AcquirePackets,
                            LogForDuration>;

struct PlannedAction {
  size_t step = 0;  ///< index of the sequence step it comes from
  uint8_t tag = 0;  ///< that step's TAG, written into every packet acquired by this action
  Action action;
  double estimate_s = 0.0;
};

/// Rig behaviour assumed by the duration estimate (E unless stated).
struct PlanTiming {
  double operator_prompt_s = 60.0;  ///< operator reads and acts (0 for a virtual fixture)
  double table_settle_s = 2.0;      ///< after a ramp, until the table reports at rate
  double interlock_sample_s = 1.0;  ///< packets averaged by an interlock check
  /// A loaded chamber's mean rate to a new set point, where the station declares none.
  double chamber_ramp_c_per_min = 1.0;
  /// The chamber's declared heating and cooling rates (station file, station_limits.h): a set
  /// point change upwards takes |change| / heat, downwards |change| / cool.
  std::optional<double> chamber_heat_c_per_min;
  std::optional<double> chamber_cool_c_per_min;
  double adts_stable_s = 15.0;       ///< ADTS "stable" flag delay (protocols.md §4.4, DRV)
  double profile_download_s = 10.0;  ///< Modbus transactions of a profile download
  double initial_chamber_c = 25.0;   ///< chamber set point before the run
  double initial_alt_ft = 0.0;       ///< ADTS at ground before the run
  double initial_cas_kt = 0.0;
};

struct ExecutionPlan {
  std::vector<PlannedAction> actions;
  double duration_estimate_s = 0.0;  ///< sum of the action estimates
};

/// Expands `sequence`. Throws SequenceError (validation.h) listing every problem when the
/// sequence is not valid against `limits`.
ExecutionPlan ExpandSequence(const Sequence& sequence,
                             const SequenceLimits& limits,
                             const PlanTiming& timing = {});

/// Duration of a profile run from the set point `start_c`, by the model in the header comment.
double ProfileDurationS(const ThermalProfileStep& profile, double start_c);

/// One line describing an action, e.g. "set table rate -150 deg/s (accel 100 deg/s^2)".
std::string Describe(const Action& action);

}  // namespace adahrs::calib
