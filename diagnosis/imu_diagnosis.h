// Diagnosis of one IMU recording against the pipeline's own forward model. Per channel the baseline
// is the joint calibration's (imu_joint_fit.h: offset, thermal cubic, scale and cross-axis; gyros
// also the span's u^2, u^3), fitted first so that only what it cannot express remains. Candidate
// terms, each one named physical effect in its own unit written from the physics (the simulator's
// vocabulary, not its code), are selected forward per channel by the jackknife Wald test over
// segments at a Bonferroni level, kept only if the leave-one-segment-out error drops; the table
// rate ripple is tested on the rows (rate_ripple.h). Errors: white per row plus a random offset
// per segment estimated from the baseline's own residuals (clustered_least_squares.h), never from
// a datasheet or the simulator; slow candidates get the recording's slow-noise floor. Then
// unexplained structure (located, not fitted) and detection limits per candidate and channel.
// Frames and units: body axes B; f_B in g, w_B in deg/s, temperatures in degC; each effect's unit
// in the vocabulary.
// Method step by step and the vocabulary: docs/diagnose.md ("Method (IMU)", "Vocabulary").
// Left out: the ADS and generic channel CSVs (ads_diagnosis.h, channel_diagnosis.h); lag and
// warm-up on gyros, thermal hysteresis on accelerometers.
#pragma once

#include <string>
#include <vector>

#include "diagnosis/diagnosis_cells.h"
#include "diagnosis/diagnosis_result.h"

namespace adahrs::diagnosis {

struct DiagnosisOptions {
  /// Nominal family-wise level per unit, Bonferroni-divided over the unit's tests. Not the rate
  /// of false findings: the jackknife over a few dozen segments is anti-conservative, and clean
  /// units give a finding at 3 % per unit for the IMU (32 of 1,100 simulated) and 2 % for the ADS
  /// (13 of 700), the levels the diagnosis states (docs/diagnose.md "Measured") and its tests
  /// hold it to.
  double family_alpha = 0.001;
  double power_z = 0.8416;  ///< z of 80 % power, for detection limits
  int max_findings_per_channel = 4;
  /// Test thermal_hysteresis (its proof and false-discovery rate: docs/diagnose.md).
  bool thermal_hysteresis_candidate = true;
};

/// Diagnoses one unit's data. Throws ImuInputError when the data cannot support the baseline.
UnitDiagnosis DiagnoseImu(const DiagnosisData& data, const DiagnosisOptions& options = {});

}  // namespace adahrs::diagnosis
