// The `--quick` variants of a campaign's sequences (docs/demo.md): the same steps, temperatures,
// orientations, rates, altitudes and airspeeds — so every fit keeps a non-degenerate design — with
// every soak (`soak_s` of target_temperature steps) cut to at most kQuickSoakS and every
// acquisition (`packets`) to at most kQuickPackets. Each variant is validated by the sequence
// reader and written to `<dir>/<name>_quick.json` with "name" "<name>_quick".
// What it costs: shorter soaks leave the dies further from the chamber air (thermal lag) and
// fewer packets raise the noise of every mean by sqrt(1000/200); the evaluation shows the result.
// Left out: trimming thermal_profile steps (their ramps are the thermal calibration's data).
#pragma once

#include <filesystem>

#include "calib/campaign/campaign.h"

namespace adahrs::calib {

inline constexpr double kQuickSoakS = 600.0;
inline constexpr int kQuickPackets = 200;

/// Writes the quick variants of `sequences` into `dir`; returns their paths.
CampaignSequences WriteQuickSequences(const CampaignSequences& sequences,
                                      const std::filesystem::path& dir);

}  // namespace adahrs::calib
