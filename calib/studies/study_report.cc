#include "calib/studies/study_report.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <fmt/format.h>

#include "calib/acceptance/specification.h"
#include "calib/report/html_builder.h"
#include "calib/report/svg_plot.h"

namespace adahrs::calib {
namespace {

constexpr int kHistogramBins = 30;
constexpr const char* kStyle =
    "body{font-family:sans-serif;max-width:70em;margin:1em auto}"
    "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:2px 6px;"
    "font-size:90%}caption{text-align:left;font-weight:bold}.unavailable{color:#a33;font-style:"
    "italic}";

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
PlotSeries Histogram(const std::string& label, const std::vector<double>& v, double top) {
  std::vector<int> counts(kHistogramBins, 0);
  for (double x : v) {
    const int bin = std::min(kHistogramBins - 1, static_cast<int>(x / top * kHistogramBins));
    ++counts[static_cast<size_t>(bin)];
  }
  PlotSeries s{label, {}, {}, PlotSeries::Style::kLine};
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

PlotSeries Cdf(const std::string& label, const std::vector<double>& v) {
  PlotSeries s{label, {}, {}, PlotSeries::Style::kLine};
  for (size_t i = 0; i < v.size(); ++i) {
    s.x.insert(s.x.end(), {v[i], v[i]});
    s.y.insert(s.y.end(),
               {static_cast<double>(i) / v.size(), static_cast<double>(i + 1) / v.size()});
  }
  return s;
}

std::string QuantityPlots(const StudyMeta& meta,
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
  Plot histogram{"worst " + name + " error per unit",
                 "worst " + name + " error (" + unit + ")",
                 "units",
                 {},
                 {}};
  Plot cdf{"cumulative distribution",
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
  if (!any) return NotAvailable(name + " plots", "no unit was fitted");
  cdf.series.push_back({"specification", {limit, limit}, {0.0, 1.0}, PlotSeries::Style::kLine});
  return RenderSvg(histogram) + "\n" + RenderSvg(cdf) + "\n";
}

std::string Settings(const StudyMeta& meta) {
  HtmlTable t{"study",
              {"units", "seed", "population", "local gravity (m/s^2)", "frames per grid point"},
              {}};
  t.rows.push_back({std::to_string(meta.units),
                    std::to_string(meta.seed),
                    meta.population,
                    FormatNumber(meta.g_local_mps2),
                    std::to_string(meta.evaluation_frames)});
  HtmlTable s{"strategies", {"name", "strategy", "sequence", "rig time (h)"}, {}};
  for (const auto& i : meta.strategies) {
    s.rows.push_back({i.name, i.strategy, i.sequence, FormatNumber(i.rig_time_s / 3600.0, 4)});
  }
  return RenderTable(t) + RenderTable(s);
}

std::string Yield(const StudySummary& summary) {
  HtmlTable t{"yield (fraction of units passing) and worst errors",
              {"strategy",
               "units",
               "fitted",
               "acceleration",
               "body rate",
               "body rate within limit",
               "all",
               "accel p50 (mg)",
               "accel p95 (mg)",
               "accel max (mg)",
               "rate p50 (deg/s)",
               "rate p95 (deg/s)",
               "rate max (deg/s)"},
              {}};
  for (const auto& s : summary.strategies) {
    t.rows.push_back({s.info.name,
                      std::to_string(s.units),
                      std::to_string(s.fitted),
                      FormatNumber(s.yield_acceleration, 4),
                      FormatNumber(s.yield_body_rate, 4),
                      FormatNumber(s.yield_body_rate_limit, 4),
                      FormatNumber(s.yield_all, 4),
                      FormatNumber(s.worst_accel_mg.p50, 4),
                      FormatNumber(s.worst_accel_mg.p95, 4),
                      FormatNumber(s.worst_accel_mg.max, 4),
                      FormatNumber(s.worst_rate_dps.p50, 4),
                      FormatNumber(s.worst_rate_dps.p95, 4),
                      FormatNumber(s.worst_rate_dps.max, 4)});
  }
  return RenderTable(t);
}

std::string Paired(const StudySummary& summary) {
  if (!summary.paired) return NotAvailable("paired comparison", "one strategy only (no --vs)");
  const PairedSummary& p = *summary.paired;
  HtmlTable t{fmt::format("paired difference {} - {} (same units, same noise; bootstrap 95 % "
                          "interval, {} resamples)",
                          p.second,
                          p.first,
                          p.resamples),
              {"quantity", "units", "mean", "95 % low", "95 % high"},
              {}};
  auto row = [&](const std::string& name, const PairedInterval& i) {
    t.rows.push_back({name,
                      std::to_string(i.units),
                      FormatNumber(i.mean, 4),
                      FormatNumber(i.ci95_low, 4),
                      FormatNumber(i.ci95_high, 4)});
  };
  row("yield, all criteria (fraction)", p.yield_all);
  row("yield, acceleration (fraction)", p.yield_acceleration);
  row("worst acceleration error (mg)", p.worst_accel_mg);
  row("worst body-rate error (deg/s)", p.worst_rate_dps);
  return RenderTable(t);
}

}  // namespace

std::string RenderStudyReport(const StudyMeta& meta,
                              const StudySummary& summary,
                              const std::vector<StudyUnitResult>& results) {
  const Specification spec = Specification::Reference();
  std::string body = Section("settings", 2, "Study", Settings(meta));
  body += Section("yield", 2, "Yield", Yield(summary));
  body += Section("paired", 2, "Paired comparison", Paired(summary));
  body +=
      Section("acceleration",
              2,
              "Worst acceleration error",
              QuantityPlots(
                  meta, results, "acceleration", "mg", spec.accel_mg, [](const StrategyOutcome& o) {
                    return o.worst_accel_mg;
                  }));
  body += Section(
      "body-rate",
      2,
      "Worst body-rate error",
      QuantityPlots(
          meta, results, "body-rate", "deg/s", spec.body_rate_dps, [](const StrategyOutcome& o) {
            return o.worst_rate_dps;
          }));
  const std::string title = "Calibration study";
  return fmt::format(
      "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\">\n<head>\n"
      "<meta "
      "charset=\"utf-8\"/>\n<title>{}</title>\n<style>{}</style>\n</head>\n<body>\n<h1>{}</h1>\n"
      "<p>Each unit is judged against the specification (acceleration {} mg, body rate {} deg/s) "
      "over the envelope grid -40...+85 degC through the firmware "
      "compensator.</p>\n{}</body>\n</html>\n",
      XmlEscape(title),
      kStyle,
      XmlEscape(title),
      FormatNumber(spec.accel_mg),
      FormatNumber(spec.body_rate_dps),
      body);
}

const char* StudyReportStyle() { return kStyle; }

std::string StudyQuantityPlots(const StudyMeta& meta,
                               const std::vector<StudyUnitResult>& results,
                               const std::string& name,
                               const std::string& unit,
                               double limit,
                               const std::function<double(const StrategyOutcome&)>& q) {
  return QuantityPlots(meta, results, name, unit, limit, q);
}

}  // namespace adahrs::calib
