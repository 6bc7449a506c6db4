// The IMU diagnosis's candidate effects, one table row each (docs/diagnose.md "Vocabulary"): the
// name the findings use, which channels it is tested on, its components, the design columns it
// adds to a cell's row, each component's physical scale and unit, whether it is a slow contrast
// between stretches of the recording (tested against the recording's own slow noise), and the
// words of a finding. Adding an effect is adding a row here.
// Frames and units: body axes B; f_B in g, w_B in deg/s, temperatures in degC; raw channel units
// (duty, counts) in the columns, `phys` converts a channel's raw unit to mg or deg/s.
// Left out: table_rate_ripple, a rig effect measured on the rows, not a column (rate_ripple.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "diagnosis/diagnosis_cells.h"
#include "diagnosis/diagnosis_result.h"

namespace adahrs::diagnosis {

enum class Effect {
  kDieLag,
  kScaleTempco,
  kCrossAxisTempco,
  kGSensitivity,
  kThermalHysteresis,
  kWarmUp,
  kAccelNonlinearity
};

/// What an effect's columns are built from, for one cell of one channel.
struct EffectInputs {
  const DiagnosisCell& cell;
  int channel = 0;
  double dudt_per_c = 0.0;   ///< slope of the baseline's thermal polynomial, raw unit per degC
  double dt_c = 0.0;         ///< thermometer temperature - 25 degC
  Eigen::Vector3d stim;      ///< the channel kind's stimulus: f_B (g) or w_B (deg/s)
  double stim_part = 0.0;    ///< the baseline's response to `stim`, raw units
  double sensitivity = 0.0;  ///< |baseline stimulus coefficient| on the channel's own axis
  std::optional<double> tau_s;
};

struct EffectUnit {
  double scale = 1.0;  ///< physical value per fitted coefficient
  std::string unit;
};

struct ImuEffect {
  Effect effect = Effect::kDieLag;
  const char* name = "";  ///< the vocabulary of docs/diagnose.md
  bool on_accel = false;
  bool on_gyro = false;
  bool needs_hysteresis_option = false;  ///< tested only with thermal_hysteresis_candidate
  /// Alternatives tested as one effect (the warm-up's time constants); empty: one candidate.
  std::vector<double> taus_s;
  /// A contrast between long stretches of the recording or between the few input levels the
  /// capture quantises: tested against the recording's slow noise too (slow_noise.h).
  bool slow = false;
  /// Its estimate carries the capture quantiser's bias per input level (an offset per segment
  /// uniform over one output step).
  bool quantised_input = false;
  /// Testable only where the cross-axis input spans temperatures (kMinCrossAxisSpan_c).
  bool needs_cross_excitation = false;
  std::vector<std::string> (*components)(int channel) = nullptr;
  void (*columns)(const EffectInputs& in, double* x) = nullptr;
  EffectUnit (*unit)(size_t component, int channel, double phys) = nullptr;
  std::string (*words)(const std::string& channel,
                       const std::string& thermometer,
                       const std::vector<FindingComponent>& c,
                       std::optional<double> tau_s) = nullptr;
};

/// Every effect, in the order their columns follow the baseline's.
const std::vector<ImuEffect>& ImuEffects();
const ImuEffect& EffectRow(Effect effect);

}  // namespace adahrs::diagnosis
