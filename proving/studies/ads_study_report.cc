#include "proving/studies/ads_study_report.h"

#include "calib/report/html_builder.h"
#include "proving/studies/study_report_parts.h"

namespace adahrs::proving {
namespace {

std::string Settings(const StudyMeta& meta) {
  calib::HtmlTable t{"study", {"unit kind", "units", "seed", "population"}, {}};
  t.rows.push_back({"ADS", std::to_string(meta.units), std::to_string(meta.seed), meta.population});
  return calib::RenderTable(t) + StudyStrategiesTable(meta);
}

std::string Yield(const AdsStudySummary& summary) {
  calib::HtmlTable t{"yield (fraction of units passing) and worst errors (in tolerances)",
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
    t.rows.push_back(
        StudyYieldRow(s.info,
                      s.units,
                      s.fitted,
                      {s.yield_altitude, s.yield_airspeed, s.yield_all, s.yield_no_history},
                      {s.worst_altitude_tol, s.worst_airspeed_tol}));
  }
  return calib::RenderTable(t);
}

std::string Paired(const AdsStudySummary& summary) {
  if (!summary.paired)
    return calib::NotAvailable("paired comparison", "one strategy only (no --vs)");
  const AdsPairedSummary& p = *summary.paired;
  return StudyPairedTable(p.first,
                          p.second,
                          p.resamples,
                          {{"yield, all criteria (fraction)", p.yield_all},
                           {"yield, altitude (fraction)", p.yield_altitude},
                           {"yield, airspeed (fraction)", p.yield_airspeed},
                           {"worst altitude error (tolerances)", p.worst_altitude_tol},
                           {"worst airspeed error (tolerances)", p.worst_airspeed_tol}});
}

}  // namespace

std::string RenderAdsStudyReport(const StudyMeta& meta,
                                 const AdsStudySummary& summary,
                                 const std::vector<StudyUnitResult>& results) {
  std::string body = calib::Section("settings", 2, "Study", Settings(meta));
  body += calib::Section("yield", 2, "Yield", Yield(summary));
  body += calib::Section("paired", 2, "Paired comparison", Paired(summary));
  body += calib::Section(
      "altitude",
      2,
      "Worst altitude error",
      StudyQuantityPlots(
          meta, results, "altitude", "tolerances", 1.0, [](const StrategyOutcome& o) {
            return o.worst_altitude_tol;
          }));
  body += calib::Section(
      "airspeed",
      2,
      "Worst airspeed error",
      StudyQuantityPlots(
          meta, results, "airspeed", "tolerances", 1.0, [](const StrategyOutcome& o) {
            return o.worst_airspeed_tol;
          }));
  return StudyPage(
      "ADS calibration study",
      "<p>Each unit is judged against the specification's altitude and airspeed tolerances over "
      "the envelope grid -1,000...50,000 ft, 30...450 kt, -40...+85 degC through the firmware "
      "compensator, under every pressure and thermal history of the evaluation; errors are in "
      "units of the tolerance at their grid point (1 = at the tolerance).</p>",
      body);
}

}  // namespace adahrs::proving
