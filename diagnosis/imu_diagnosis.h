// Diagnosis of one IMU recording against the pipeline's own forward model (docs/diagnose.md).
//
// Baseline, per channel, what the reference method and the joint calibration assume
// (imu_joint_fit.h), fitted to this recording first so that only what the model cannot express
// remains:
//   accelerometer:  U = o + a1 s + a2 s^2 + a3 s^3 + m . f_B_g
//   gyro:           U = c + b1 s + b2 s^2 + b3 s^3 + n . w_B_dps + q2 u^2 + q3 u^3
// s = (T - 25 degC) / 62.5 degC of the channel's thermometer, u = w_axis / 150 deg/s.
// Candidate terms, each one named physical effect in its own unit, written from the physics
// (they share the simulator's vocabulary, not its code); lag and warm-up only for the
// accelerometers (a gyro's thermometer is its own die's TEMP pin), thermal hysteresis only for the
// gyros (an accelerometer's lag transients after each ramp carry the sense of the last change):
//   die_thermal_lag          -dU/dT * dT/dt            delay of the die behind its thermometer, s
//   scale_factor_tempco      (stimulus part) * dT, dT^2   ppm/degC, ppm/degC^2
//   residual_cross_axis_coupling  |S| * (off-axis rate) * dT, per off axis   ppm/degC (gyros)
//   gyro_g_sensitivity       f_B_g x, y, z             deg/s/g (gyros)
//   thermal_hysteresis       sense of the last change  half the up/down loop, deg/s (gyros)
//   self_heating_warm_up     dU/dT * exp(-t/tau_w)     the die's excess at power-on, degC
//                            (tau_w from a grid: 150, 300, 600, 1200 s)
//   accel_nonlinearity       |S| f_axis^2              mg/g^2 (accelerometers)
// and, on the rows rather than the cells, table_rate_ripple: a line at the table's revolution
// frequency on the gyro along the table axis, in ppm of the rate (rate_ripple.h; a rig effect).
// Errors: white per row plus a random offset per segment whose variance is estimated from the
// baseline's own residuals (clustered_least_squares.h), never from a datasheet or the simulator;
// the slow candidates (hysteresis, warm-up, nonlinearity: contrasts between stretches) are weighted
// by white noise alone, with the recording's measured slow wander as their variance floor.
// Selection, per channel: forward, one candidate at a time, by the jackknife Wald test over
// segments (clustered_least_squares.h) against an F(q, C-1) quantile at a Bonferroni level over
// every (channel, candidate) test of the unit, and only if the leave-one-segment-out error drops.
// Dependent columns (dU/dT, the stimulus part) are rebuilt from the final baseline once.
// Unexplained structure, after the final model: a segment whose held-out mean residual lies far
// outside the others' (robust scale), an abrupt step inside a long segment, and a periodic line in
// the rows' spectra (row_spectrum.h) above half the output's step. None is fitted.
// Detection limits: per candidate and channel, (t_crit + 0.84) standard errors of the candidate
// added alone to the final model (80 % power at the selection's level).
// Not done: the ADS, generic channel CSVs.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "diagnosis/diagnosis_cells.h"

namespace adahrs::diagnosis {

struct DiagnosisOptions {
  /// Family-wise level per unit, Bonferroni-divided over the unit's tests. Set ten times below
  /// the 1 % aimed at: the jackknife over a few dozen segments is anti-conservative by about that
  /// (measured on clean units, docs/diagnose.md).
  double family_alpha = 0.001;
  double power_z = 0.8416;  ///< z of 80 % power, for detection limits
  int max_findings_per_channel = 4;
  /// Test thermal_hysteresis (its proof and false-discovery rate: docs/diagnose.md).
  bool thermal_hysteresis_candidate = true;
};

struct FindingComponent {
  std::string name;  ///< "delay", "x", "tc1", ...
  double magnitude = 0.0;
  double standard_error = 0.0;
  std::string unit;  ///< "s", "mg", "dps", "degC", "ppm/degC", "ppm/degC^2", "mg/g^2", "dps/g"
  nlohmann::json ToJson() const;
};

struct Finding {
  std::string effect;   ///< vocabulary of docs/diagnose.md
  std::string channel;  ///< az1 ... gz
  std::vector<FindingComponent> components;
  std::optional<double> time_constant_s;  ///< self_heating_warm_up's chosen tau_w
  double wald_p_value = 0.0;
  double held_out_rms_before = 0.0;  ///< the final model without this term, channel unit
  double held_out_rms_after = 0.0;   ///< the final model
  std::string rms_unit;
  std::vector<std::string> evidence;  ///< segments where the term contributes most
  std::string words;
  nlohmann::json ToJson() const;
};

struct Unexplained {
  std::string channel;
  std::string where;
  std::string description;
  double size = 0.0;
  std::string unit;
  nlohmann::json ToJson() const;
};

struct DetectionLimit {
  std::string effect;
  std::string channel;
  std::vector<FindingComponent> limits;  ///< magnitude = smallest detectable; empty when untestable
  std::string note;                      ///< why it cannot be tested, when it cannot
  nlohmann::json ToJson() const;
};

struct ChannelFitSummary {
  std::string channel;
  std::string unit;
  double held_out_rms_baseline = 0.0;
  double held_out_rms_final = 0.0;
  double white_noise_rms = 0.0;  ///< what white noise alone would leave in a cell mean, median
  std::vector<std::string> baseline_terms;
  /// For the report's figures (not in ToJson): cell times, thermometer temperature and the
  /// residual of the baseline and of the final model, channel unit, at most kPlotCells cells.
  std::vector<double> plot_t_s, plot_temp_c, plot_residual_baseline, plot_residual_final;
  nlohmann::json ToJson() const;
};

inline constexpr int kPlotCells = 1500;

struct UnitDiagnosis {
  std::string serial;
  int rows = 0;
  int segments = 0;
  int cells = 0;
  double temp_span_c = 0.0;
  bool thermometers_fitted = false;
  int tests = 0;            ///< (channel, candidate) tests the Bonferroni level divides by
  double test_alpha = 0.0;  ///< per test
  std::vector<Finding> findings;
  std::vector<Unexplained> unexplained;
  std::vector<DetectionLimit> detection_limits;
  std::vector<ChannelFitSummary> channels;
  std::vector<std::string> notes;
  nlohmann::json ToJson() const;
};

/// Diagnoses one unit's data. Throws ImuInputError when the data cannot support the baseline.
UnitDiagnosis DiagnoseImu(const DiagnosisData& data, const DiagnosisOptions& options = {});

}  // namespace adahrs::diagnosis
