// The held-out re-simulation check as files: replay_check.json (one ReplayComparison per checked
// run) and replay_check.html (per run and unit a table of each channel's RMS with the base model,
// with model.json and from the noise alone, and a figure per channel where either model leaves
// more than twice the noise: each acquisition's mean residual, recorded − replayed, with a band of
// ±2 of its standard errors).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "diagnosis/replay_comparison.h"

namespace adahrs::diagnosis {

std::string ReplayCheckHtml(const std::vector<ReplayComparison>& checks);

/// Writes `out_dir`/replay_check.json and replay_check.html, each atomically.
void WriteReplayCheck(const std::vector<ReplayComparison>& checks,
                      const std::filesystem::path& out_dir);

}  // namespace adahrs::diagnosis
