// The parts every study's report.html is made of (study_report.h for IMU studies,
// ads_study_report.h for ADS studies): the page and its style sheet, the strategies table, a
// yield row, the paired-difference table, and per quantity a histogram and an empirical CDF of
// every strategy on one plot with the specification's limit drawn on the CDF. Plots are the
// project's inline SVG (svg_plot.h); the page is XHTML like report.html of a run (html_builder.h).
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "proving/studies/study_results.h"

namespace adahrs::proving {

/// The XHTML page: `title` as heading, `intro_html` (a paragraph) before `body`.
std::string StudyPage(const std::string& title,
                      const std::string& intro_html,
                      const std::string& body);

/// The table of the study's strategies (name, strategy, sequence, rig time).
std::string StudyStrategiesTable(const StudyMeta& meta);

/// One strategy's row of a yield table: name, units, fitted, each yield, then p50, p95 and max
/// of each error distribution.
std::vector<std::string> StudyYieldRow(const StudyStrategyInfo& info,
                                       int units,
                                       int fitted,
                                       const std::vector<double>& yields,
                                       const std::vector<ErrorDistribution>& errors);

/// The paired differences second − first, one row per named interval.
std::string StudyPairedTable(const std::string& first,
                             const std::string& second,
                             int resamples,
                             const std::vector<std::pair<std::string, PairedInterval>>& rows);

/// Histogram and empirical CDF of quantity `q` of every strategy, `limit` drawn on the CDF.
std::string StudyQuantityPlots(const StudyMeta& meta,
                               const std::vector<StudyUnitResult>& results,
                               const std::string& name,
                               const std::string& unit,
                               double limit,
                               const std::function<double(const StrategyOutcome&)>& q);

}  // namespace adahrs::proving
