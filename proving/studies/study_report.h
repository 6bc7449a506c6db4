// report.html of an IMU study: the settings, a yield table per strategy and criterion, the
// worst-error distributions (table of percentiles, histogram and empirical CDF per quantity,
// every strategy on one plot, the specification's limit drawn as a vertical line) and, with two
// strategies, the paired differences with their bootstrap intervals (the parts:
// study_report_parts.h). Left out: per-unit plots (results.csv holds every unit).
#pragma once

#include <string>
#include <vector>

#include "proving/studies/study_results.h"

namespace adahrs::proving {

std::string RenderStudyReport(const StudyMeta& meta,
                              const StudySummary& summary,
                              const std::vector<StudyUnitResult>& results);

}  // namespace adahrs::proving
