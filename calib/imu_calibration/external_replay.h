// The replay of an external strategy's fits (docs/strategies-external.md "Replaying a fit"): each
// constants file of a fit directory that an external program produced is checked against what
// was kept beside it (the request's SHA-256), its program is run again on that request, and the
// new reply's constants are compared with the file's, number by number (bit for bit: a program
// that is a function of its request gives the same numbers).
// Left out: built-in strategies (refit them from the recordings named in the provenance).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace adahrs::calib {

struct ExternalReplayOutcome {
  std::string serial;
  std::string strategy_file;        ///< the file whose program ran
  bool strategy_unchanged = false;  ///< its SHA-256 is the one recorded
  bool reply_identical = false;     ///< the new reply's bytes are the kept reply's
  bool constants_identical = false;
  std::string difference;  ///< the first constant that differs: JSON path, kept and new values
  double elapsed_s = 0.0;
  nlohmann::json ToJson() const;
};

/// Replays every external fit in `fit_dir` (files whose provenance has "external"), with the
/// strategy file recorded or `strategy_file` instead. Throws ExternalStrategyError when a kept
/// request is missing or not the one recorded, or the program fails or its reply is refused;
/// ImuInputError when the directory holds no external fit.
std::vector<ExternalReplayOutcome> ReplayExternalFits(
    const std::filesystem::path& fit_dir,
    const std::optional<std::filesystem::path>& strategy_file = std::nullopt);

}  // namespace adahrs::calib
