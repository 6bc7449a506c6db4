// Diagnosis of a generic channel recording (channel_recording.h: a barometer or MEMS sensor
// logged elsewhere) against a model written from the physics of any thermally sensitive
// transducer (docs/diagnose.md "Generic channel CSV"). Per output:
//   y = b0 + b1 s + ... + bd s^d + sum_r (m_r + n_r s) x_r,   s = (T - T_mid) / T_half
// bias(T) of degree d (1...3, chosen by the leave-one-segment-out error) and, for each reference
// input x_r, a scale and its temperature coefficient. Candidates, each in its own unit:
//   thermal_lag           -dU/dT * dT/dt            the element lags the thermometer: delay, s
//   thermal_hysteresis    sense of the last change  half the loop, output unit
//   self_heating_warm_up  dU/dT * exp(-t/tau)       the element's excess over the thermometer at
//   the
//                                                   first row, degC (tau in 150, 300, 600, 1200 s)
// Segments: stretches without a gap longer than max_gap_s (10 median intervals unless the
// sidecar says), cut every kChannelSegment_s; cells of 1 s. A cell's temperature rate is the
// least-squares slope of the cells' temperatures within +-W, W = max(30 s, 1.1 x the median
// spacing of segment starts), so sparse bursts take their rate from their neighbours.
// Selection and limits as for the IMU (term_selection.h) at the family level over the recording's
// tests; periodic lines in the rows (row_spectrum.h, windows of the largest power of two up to
// 512 rows that the median segment holds, at least 64), below half a stated resolution noted only.
// Not done: cross-coupling between outputs, a model of the reference inputs' own errors.
#pragma once

#include "diagnosis/channel_recording.h"
#include "diagnosis/imu_diagnosis.h"

namespace adahrs::diagnosis {

inline constexpr double kChannelSegment_s = 120.0;

/// Throws ChannelInputError when the recording has fewer than 3 segments or a baseline cannot be
/// fitted.
UnitDiagnosis DiagnoseChannels(const ChannelRecording& recording,
                               const DiagnosisOptions& options = {});

}  // namespace adahrs::diagnosis
