// The report's acceptance section (docs/report.md): per unit, from its acceptance.json
// (calib/acceptance/acceptance_file.h, docs/acceptance.md), the overall verdict, the worst margin
// per quantity and one row per judged point — step, kind, quantity, condition, measured,
// reference, error with its standard error, tolerance, margin (each in the point's unit) and
// PASS/FAIL, as ReadAcceptanceFile read them.
// Left out: figures (the ADS error map and IMU residual figures show the calibration run).
#pragma once

#include <string>
#include <vector>

#include "calib/acceptance/acceptance_file.h"
#include "calib/report/html_builder.h"

namespace adahrs::calib {

/// The unit's worst margin per quantity: quantity, margin, unit, step, point, PASS/FAIL.
HtmlTable WorstMarginTable(const UnitAcceptance& unit);

/// The section body for the acceptance files of a run (one document per unit).
std::string AcceptanceSectionBody(const std::vector<AcceptanceFile>& files);

}  // namespace adahrs::calib
