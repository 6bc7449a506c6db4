#include "proving/studies/study_report_parts.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "calib/report/html_builder.h"
#include "calib/report/svg_plot.h"
#include "common/html_page.h"

namespace adahrs::proving {
namespace {

constexpr int kHistogramBins = 30;

using Quantity = std::function<double(const StrategyOutcome&)>;

std::vector<double> Finite(const std::vector<StudyUnitResult>& results,
                           size_t s,
                           const Quantity& q) {
  std::vector<double> v;
  for (const auto& r : results) {
    const double x = q(r.outcomes.at(s));
    if (std::isfinite(x)) v.push_back(x);
  }
  std::sort(v.begin(), v.end());
  return v;
}

// Outline of a histogram over [0, top]: units per bin as a step line.
calib::PlotSeries Histogram(const std::string& label, const std::vector<double>& v, double top) {
  std::vector<int> counts(kHistogramBins, 0);
  for (double x : v) {
    const int bin = std::min(kHistogramBins - 1, static_cast<int>(x / top * kHistogramBins));
    ++counts[static_cast<size_t>(bin)];
  }
  calib::PlotSeries s{label, {}, {}, calib::PlotSeries::Style::kLine};
  for (int b = 0; b < kHistogramBins; ++b) {
    const double lo = top * b / kHistogramBins, hi = top * (b + 1) / kHistogramBins;
    s.x.insert(s.x.end(), {lo, lo, hi, hi});
    s.y.insert(s.y.end(),
               {0.0,
                static_cast<double>(counts[static_cast<size_t>(b)]),
                static_cast<double>(counts[static_cast<size_t>(b)]),
                0.0});
  }
  return s;
}

calib::PlotSeries Cdf(const std::string& label, const std::vector<double>& v) {
  calib::PlotSeries s{label, {}, {}, calib::PlotSeries::Style::kLine};
  for (size_t i = 0; i < v.size(); ++i) {
    s.x.insert(s.x.end(), {v[i], v[i]});
    s.y.insert(s.y.end(),
               {static_cast<double>(i) / v.size(), static_cast<double>(i + 1) / v.size()});
  }
  return s;
}

}  // namespace

std::string StudyPage(const std::string& title,
                      const std::string& intro_html,
                      const std::string& body) {
  return common::HtmlPage(
      title, fmt::format("<h1>{}</h1>\n{}\n{}", calib::XmlEscape(title), intro_html, body));
}

std::string StudyStrategiesTable(const StudyMeta& meta) {
  calib::HtmlTable s{"strategies", {"name", "strategy", "sequence", "rig time (h)"}, {}};
  for (const auto& i : meta.strategies) {
    s.rows.push_back(
        {i.name, i.strategy, i.sequence, calib::FormatNumber(i.rig_time_s / 3600.0, 4)});
  }
  return calib::RenderTable(s);
}

std::vector<std::string> StudyYieldRow(const StudyStrategyInfo& info,
                                       int units,
                                       int fitted,
                                       const std::vector<double>& yields,
                                       const std::vector<ErrorDistribution>& errors) {
  std::vector<std::string> row{info.name, std::to_string(units), std::to_string(fitted)};
  for (double y : yields) row.push_back(calib::FormatNumber(y, 4));
  for (const ErrorDistribution& e : errors) {
    for (double x : {e.p50, e.p95, e.max}) row.push_back(calib::FormatNumber(x, 4));
  }
  return row;
}

std::string StudyPairedTable(const std::string& first,
                             const std::string& second,
                             int resamples,
                             const std::vector<std::pair<std::string, PairedInterval>>& rows) {
  calib::HtmlTable t{
      fmt::format("paired difference {} - {} (same units, same noise; bootstrap 95 % "
                  "interval, {} resamples)",
                  second,
                  first,
                  resamples),
      {"quantity", "units", "mean", "95 % low", "95 % high"},
      {}};
  for (const auto& [name, i] : rows) {
    t.rows.push_back({name,
                      std::to_string(i.units),
                      calib::FormatNumber(i.mean, 4),
                      calib::FormatNumber(i.ci95_low, 4),
                      calib::FormatNumber(i.ci95_high, 4)});
  }
  return calib::RenderTable(t);
}

std::string StudyQuantityPlots(const StudyMeta& meta,
                               const std::vector<StudyUnitResult>& results,
                               const std::string& name,
                               const std::string& unit,
                               double limit,
                               const Quantity& q) {
  std::vector<std::vector<double>> values;
  double top = limit;
  for (size_t s = 0; s < meta.strategies.size(); ++s) {
    values.push_back(Finite(results, s, q));
    if (!values.back().empty()) top = std::max(top, values.back().back());
  }
  top *= 1.05;
  calib::Plot histogram{"worst " + name + " error per unit",
                        "worst " + name + " error (" + unit + ")",
                        "units",
                        {},
                        {}};
  calib::Plot cdf{"cumulative distribution",
                  "worst " + name + " error (" + unit + ")",
                  "fraction of units",
                  {},
                  {}};
  bool any = false;
  for (size_t s = 0; s < values.size(); ++s) {
    if (values[s].empty()) continue;
    any = true;
    histogram.series.push_back(Histogram(meta.strategies[s].name, values[s], top));
    cdf.series.push_back(Cdf(meta.strategies[s].name, values[s]));
  }
  if (!any) return calib::NotAvailable(name + " plots", "no unit was fitted");
  cdf.series.push_back(
      {"specification", {limit, limit}, {0.0, 1.0}, calib::PlotSeries::Style::kLine});
  return calib::RenderSvg(histogram) + "\n" + calib::RenderSvg(cdf) + "\n";
}

}  // namespace adahrs::proving
