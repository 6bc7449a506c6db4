// Diagnosis of one ADS unit's calibration points against the pipeline's forward model of its two
// pressure bridges (docs/diagnose.md "ADS"). Per bridge (channel "ps": static, "pt": pitot) each
// point's output code is predicted from the pressure the test set applied and the bridge's own
// voltage code (its thermometer):
//   code = sum_{a <= dp, c <= dv_a} k_ac u^a v^c,  u, v: pressure and voltage code scaled to [-1,
//   1]
// the bivariate polynomial the calibration inverts, its degrees (dp 2..3, dv_a 1..7) chosen by the
// error at each interior chamber temperature under the fit made without it (coordinate descent over
// the voltage degree of each power of u). Segments are sweeps: consecutive points at one chamber
// temperature along which one reference pressure moves one way. Candidates, each in Pa through the
// bridge's mean sensitivity dcode/dP:
//   pressure_hysteresis   s_P: state of the bridge's pressure history under the Preisach law the
//                         unit's firmware runs (bridge_history.h, the class's nominal spans); half
//                         loop
//   thermal_hysteresis    s_T: likewise of the chamber temperature; half loop
//   bridge_nonlinearity   u^(dp+1) (1, v): beyond the modelled order; the deviation at the largest
//                         travel and its change across the temperature span
// Selection as for the IMU (term_selection.h): forward, by the jackknife Wald test over sweeps at a
// Bonferroni level over the unit's six tests, kept only if the leave-one-sweep-out error drops.
// When a hysteresis term is chosen its spans are fitted to the points (hysteresis_span_fit.h,
// the calibration's profile search) and the selection is made again with them.
// Not done: unexplained structure (the pitot's residual at its top points is the baseline's own,
// so a point-outlier rule misfires), die lag and self-heating (a point is a mean after a soak: no
// time structure left), ADC integral nonlinearity.
#pragma once

#include <vector>

#include "calib/ads_calibration/ads_calibration_points.h"
#include "diagnosis/imu_diagnosis.h"

namespace adahrs::diagnosis {

/// Diagnoses one ADS unit's points (in step order, as SelectAdsCalibrationPoints returns them).
/// Throws std::runtime_error naming the unit when there are too few sweeps or points to fit.
UnitDiagnosis DiagnoseAds(const std::string& serial,
                          const std::vector<calib::AdsCalibrationPoint>& points,
                          const DiagnosisOptions& options = {});

}  // namespace adahrs::diagnosis
