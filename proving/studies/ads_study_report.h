// report.html of an ADS study: the settings, a yield table per strategy and criterion (altitude,
// airspeed, all, no history), the worst-error distributions in tolerances (percentiles; histogram
// and empirical CDF per quantity, every strategy on one plot, the tolerance drawn at 1) and, with
// two strategies, the paired differences with their bootstrap intervals. The page layout and
// plots are the IMU study's (study_report_parts.h).
#pragma once

#include <string>
#include <vector>

#include "proving/studies/ads_study_results.h"

namespace adahrs::proving {

std::string RenderAdsStudyReport(const StudyMeta& meta,
                                 const AdsStudySummary& summary,
                                 const std::vector<StudyUnitResult>& results);

}  // namespace adahrs::proving
