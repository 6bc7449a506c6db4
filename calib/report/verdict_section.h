// Page one of report.html (docs/report.md "Verdict"): what an engineer reads first. For a judged
// run, one row per unit from its acceptance.json: the outcome (PASS, MARGINAL or FAIL), the
// points failed and marginal of those judged, and each quantity's worst margin (tolerance -
// |error|, in its unit, where it was judged); then the specification judged against (name,
// version, SHA-256). With thermal acceptance points (acceptance_judge.h), a table per unit of the
// largest body-rate and acceleration standard deviation against its limit and the pair's outcome.
// A run without acceptance files says it was not judged, and where a verdict would come from. The
// details follow in the acceptance section.
#pragma once

#include <string>
#include <vector>

#include "calib/acceptance/acceptance_file.h"

namespace adahrs::calib {

/// The verdict section's body for a run's acceptance files (may be empty: not judged).
std::string VerdictSectionBody(const std::vector<AcceptanceFile>& files,
                               const std::string& sequence_name);

}  // namespace adahrs::calib
