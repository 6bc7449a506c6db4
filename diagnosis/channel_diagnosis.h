// Diagnosis of a generic channel recording (channel_recording.h: a barometer or MEMS sensor logged
// elsewhere) against a model written from the physics of any thermally sensitive transducer: per
// output, bias(T) of degree 1...3 (chosen by the leave-one-segment-out error) plus, for each
// reference input, a scale and its temperature coefficient. Candidates thermal_lag,
// thermal_hysteresis and self_heating_warm_up; selection, limits and periodic lines as for the IMU
// (term_selection.h, row_spectrum.h). Segments are stretches without a gap longer than max_gap_s,
// cut every segment_s (the sidecar's, default 120 s); cells of 1 s.
// Units: the sidecar's output and reference units; temperature in degC, delay and tau in s.
// Model, segments, temperature rate window, measured figures: docs/diagnose.md ("Generic channel
// CSV").
// Left out: cross-coupling between outputs, a model of the reference inputs' own errors.
#pragma once

#include "diagnosis/channel_recording.h"
#include "diagnosis/imu_diagnosis.h"

namespace adahrs::diagnosis {

/// Throws ChannelInputError when the recording has fewer than 3 segments (saying the segment cut
/// and the sidecar options that change it) or a baseline cannot be fitted.
UnitDiagnosis DiagnoseChannels(const ChannelRecording& recording,
                               const DiagnosisOptions& options = {});

}  // namespace adahrs::diagnosis
