// report.html of a study: the settings, a yield table per strategy and criterion, the worst-error
// distributions (table of percentiles, histogram and empirical CDF per quantity, every strategy
// on one plot, the specification's limit drawn as a vertical line) and, with two strategies, the
// paired differences with their bootstrap intervals. Plots are the project's inline SVG
// (svg_plot.h); the page is XHTML like report.html of a run (html_builder.h).
// Left out: per-unit plots (results.csv holds every unit).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "calib/studies/study_results.h"

namespace adahrs::calib {

std::string RenderStudyReport(const StudyMeta& meta,
                              const StudySummary& summary,
                              const std::vector<StudyUnitResult>& results);

// Shared with the ADS study's report (ads_study_report.h).
/// The page's style sheet.
const char* StudyReportStyle();
/// Histogram and empirical CDF of quantity `q` of every strategy, `limit` drawn on the CDF.
std::string StudyQuantityPlots(const StudyMeta& meta,
                               const std::vector<StudyUnitResult>& results,
                               const std::string& name,
                               const std::string& unit,
                               double limit,
                               const std::function<double(const StrategyOutcome&)>& q);

}  // namespace adahrs::calib
