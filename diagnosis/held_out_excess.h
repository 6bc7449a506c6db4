// A held-out error the noise model cannot account for: when a channel's final held-out RMS (leave
// one segment out, of the cell or point means) is at least kHeldOutExcessRatio times what the
// noise model alone leaves in a mean (its white noise), the model does not explain the recording,
// whatever the candidates say. It is reported as unexplained structure, naming the segments whose
// own held-out RMS is largest, so that no verdict says "no missing physics found" while it stands.
// Units: the summary's (the channel's physical unit).
// Left out: channels without a noise model (white_noise_rms 0: the ADS's step means).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "diagnosis/clustered_least_squares.h"
#include "diagnosis/diagnosis_result.h"

namespace adahrs::diagnosis {

inline constexpr double kHeldOutExcessRatio = 3.0;

/// The unexplained entry for `summary`'s channel when its held-out RMS is at least
/// kHeldOutExcessRatio times its white noise; `final_fit`'s per-segment held-out sums (times
/// `scale`, raw to physical) locate it, `labels` names the segments.
std::optional<Unexplained> HeldOutExcess(const ChannelFitSummary& summary,
                                         const ClusteredFit& final_fit,
                                         const std::vector<std::string>& labels,
                                         double scale);

}  // namespace adahrs::diagnosis
