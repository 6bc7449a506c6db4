// Diagnosis of one ADS unit's calibration points against the pipeline's forward model of its two
// pressure bridges ("ps" static, "pt" pitot): each point's code predicted from the applied
// pressure and the bridge's own voltage code (its thermometer) by the bivariate polynomial the
// calibration inverts, its degrees chosen by held-out chamber temperatures (points at one
// temperature: a polynomial in pressure alone, degree chosen by held-out sweeps, thermal
// hysteresis not testable; two or three temperatures are refused). Segments are sweeps.
// Candidates pressure_hysteresis, thermal_hysteresis (Preisach states of the reference history,
// bridge_history.h) and bridge_nonlinearity, selected as for the IMU (term_selection.h); a chosen
// hysteresis gets its spans fitted (hysteresis_span_fit.h) and the selection made again.
// Units: every candidate in Pa through the bridge's mean dcode/dP; spans in Pa and degC.
// Baseline, candidates, selection and why: docs/diagnose.md ("ADS", "Vocabulary").
// Left out: unexplained structure (point outliers misfire on the pitot's top points), die lag and
// self-heating (a point is a mean after a soak), ADC integral nonlinearity (inside the baseline's
// span).
#pragma once

#include <vector>

#include "calib/ads_calibration/ads_calibration_points.h"
#include "diagnosis/imu_diagnosis.h"

namespace adahrs::diagnosis {

/// Diagnoses one ADS unit's points (in step order, as SelectAdsCalibrationPoints returns them).
/// Throws std::runtime_error naming the unit when there are too few sweeps or points to fit, or
/// two or three chamber temperatures.
UnitDiagnosis DiagnoseAds(const std::string& serial,
                          const std::vector<calib::AdsCalibrationPoint>& points,
                          const DiagnosisOptions& options = {});

}  // namespace adahrs::diagnosis
