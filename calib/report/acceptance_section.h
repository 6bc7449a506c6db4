// The report's acceptance section (docs/report.md): per unit, from its acceptance.json
// (calib/acceptance/acceptance_file.h, docs/acceptance.md), the overall verdict, the worst margin
// per quantity and one row per judged point — step, kind, quantity, condition, measured,
// reference, error with its standard error, tolerance, margin (each in the point's unit) and
// PASS/FAIL, as ReadAcceptanceFile read them. For an IMU, between the worst margins and the points,
// the reference method's acceptance figures: per orientation the acceleration error against
// chamber temperature (Fig. 66) and the body-rate error against the commanded rate (Fig. 67) over
// the tolerance band (and the physical limit's band), then a thermal_profile step's per-bin errors
// with the thermal acceptance's standard deviations (Fig. 68).
// Left out: ADS figures here (the unit's error map in its own section shows the acceptance run).
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
