#include "calib/studies/ads_study_report.h"

#include <fmt/format.h>

#include "calib/report/html_builder.h"
#include "calib/report/svg_plot.h"
#include "calib/studies/study_report.h"

namespace adahrs::calib {
namespace {

std::string Settings(const StudyMeta& meta) {
  HtmlTable t{"study", {"unit kind", "units", "seed", "population"}, {}};
  t.rows.push_back({"ADS", std::to_string(meta.units), std::to_string(meta.seed), meta.population});
  HtmlTable s{"strategies", {"name", "strategy", "sequence", "rig time (h)"}, {}};
  for (const auto& i : meta.strategies) {
    s.rows.push_back({i.name, i.strategy, i.sequence, FormatNumber(i.rig_time_s / 3600.0, 4)});
  }
  return RenderTable(t) + RenderTable(s);
}

std::string Yield(const AdsStudySummary& summary) {
  HtmlTable t{"yield (fraction of units passing) and worst errors (in tolerances)",
              {"strategy",
               "units",
               "fitted",
               "altitude",
               "airspeed",
               "all",
               "no history",
               "altitude p50",
               "altitude p95",
               "altitude max",
               "airspeed p50",
               "airspeed p95",
               "airspeed max"},
              {}};
  for (const auto& s : summary.strategies) {
    t.rows.push_back({s.info.name,
                      std::to_string(s.units),
                      std::to_string(s.fitted),
                      FormatNumber(s.yield_altitude, 4),
                      FormatNumber(s.yield_airspeed, 4),
                      FormatNumber(s.yield_all, 4),
                      FormatNumber(s.yield_no_history, 4),
                      FormatNumber(s.worst_altitude_tol.p50, 4),
                      FormatNumber(s.worst_altitude_tol.p95, 4),
                      FormatNumber(s.worst_altitude_tol.max, 4),
                      FormatNumber(s.worst_airspeed_tol.p50, 4),
                      FormatNumber(s.worst_airspeed_tol.p95, 4),
                      FormatNumber(s.worst_airspeed_tol.max, 4)});
  }
  return RenderTable(t);
}

std::string Paired(const AdsStudySummary& summary) {
  if (!summary.paired) return NotAvailable("paired comparison", "one strategy only (no --vs)");
  const AdsPairedSummary& p = *summary.paired;
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
  row("yield, altitude (fraction)", p.yield_altitude);
  row("yield, airspeed (fraction)", p.yield_airspeed);
  row("worst altitude error (tolerances)", p.worst_altitude_tol);
  row("worst airspeed error (tolerances)", p.worst_airspeed_tol);
  return RenderTable(t);
}

}  // namespace

std::string RenderAdsStudyReport(const StudyMeta& meta,
                                 const AdsStudySummary& summary,
                                 const std::vector<StudyUnitResult>& results) {
  std::string body = Section("settings", 2, "Study", Settings(meta));
  body += Section("yield", 2, "Yield", Yield(summary));
  body += Section("paired", 2, "Paired comparison", Paired(summary));
  body += Section("altitude",
                  2,
                  "Worst altitude error",
                  StudyQuantityPlots(
                      meta, results, "altitude", "tolerances", 1.0, [](const StrategyOutcome& o) {
                        return o.worst_altitude_tol;
                      }));
  body += Section("airspeed",
                  2,
                  "Worst airspeed error",
                  StudyQuantityPlots(
                      meta, results, "airspeed", "tolerances", 1.0, [](const StrategyOutcome& o) {
                        return o.worst_airspeed_tol;
                      }));
  const std::string title = "ADS calibration study";
  return fmt::format(
      "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\">\n<head>\n"
      "<meta "
      "charset=\"utf-8\"/>\n<title>{}</title>\n<style>{}</style>\n</head>\n<body>\n<h1>{}</h1>\n"
      "<p>Each unit is judged against the specification's altitude and airspeed tolerances over "
      "the envelope grid -1,000...50,000 ft, 30...450 kt, -40...+85 degC through the firmware "
      "compensator, under every pressure and thermal history of the evaluation; errors are in "
      "units of the tolerance at their grid point (1 = at the tolerance).</p>\n{}</body>\n"
      "</html>\n",
      XmlEscape(title),
      StudyReportStyle(),
      XmlEscape(title),
      body);
}

}  // namespace adahrs::calib
