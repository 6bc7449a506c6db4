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

#include <string>
#include <vector>

#include "diagnosis/diagnosis_cells.h"
#include "diagnosis/diagnosis_result.h"

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

/// Diagnoses one unit's data. Throws ImuInputError when the data cannot support the baseline.
UnitDiagnosis DiagnoseImu(const DiagnosisData& data, const DiagnosisOptions& options = {});

}  // namespace adahrs::diagnosis
