#include "proving/studies/study_report.h"

#include <fmt/format.h>

#include "calib/acceptance/specification.h"
#include "calib/report/html_builder.h"
#include "proving/studies/study_report_parts.h"

namespace adahrs::proving {
namespace {

std::string Settings(const StudyMeta& meta) {
  calib::HtmlTable t{
      "study",
      {"units", "seed", "population", "local gravity (m/s^2)", "frames per grid point"},
      {}};
  t.rows.push_back({std::to_string(meta.units),
                    std::to_string(meta.seed),
                    meta.population,
                    calib::FormatNumber(meta.g_local_mps2),
                    std::to_string(meta.evaluation_frames)});
  return calib::RenderTable(t) + StudyStrategiesTable(meta);
}

std::string Yield(const StudySummary& summary) {
  calib::HtmlTable t{"yield (fraction of units passing) and worst errors",
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
    t.rows.push_back(StudyYieldRow(
        s.info,
        s.units,
        s.fitted,
        {s.yield_acceleration, s.yield_body_rate, s.yield_body_rate_limit, s.yield_all},
        {s.worst_accel_mg, s.worst_rate_dps}));
  }
  return calib::RenderTable(t);
}

std::string Paired(const StudySummary& summary) {
  if (!summary.paired)
    return calib::NotAvailable("paired comparison", "one strategy only (no --vs)");
  const PairedSummary& p = *summary.paired;
  return StudyPairedTable(p.first,
                          p.second,
                          p.resamples,
                          {{"yield, all criteria (fraction)", p.yield_all},
                           {"yield, acceleration (fraction)", p.yield_acceleration},
                           {"worst acceleration error (mg)", p.worst_accel_mg},
                           {"worst body-rate error (deg/s)", p.worst_rate_dps}});
}

}  // namespace

std::string RenderStudyReport(const StudyMeta& meta,
                              const StudySummary& summary,
                              const std::vector<StudyUnitResult>& results) {
  const calib::Specification spec = calib::Specification::Reference();
  std::string body = calib::Section("settings", 2, "Study", Settings(meta));
  body += calib::Section("yield", 2, "Yield", Yield(summary));
  body += calib::Section("paired", 2, "Paired comparison", Paired(summary));
  body += calib::Section(
      "acceleration",
      2,
      "Worst acceleration error",
      StudyQuantityPlots(
          meta, results, "acceleration", "mg", spec.accel_mg, [](const StrategyOutcome& o) {
            return o.worst_accel_mg;
          }));
  body += calib::Section(
      "body-rate",
      2,
      "Worst body-rate error",
      StudyQuantityPlots(
          meta, results, "body-rate", "deg/s", spec.body_rate_dps, [](const StrategyOutcome& o) {
            return o.worst_rate_dps;
          }));
  return StudyPage("Calibration study",
                   fmt::format("<p>Each unit is judged against the specification (acceleration "
                               "{} mg, body rate {} deg/s) over the envelope grid -40...+85 degC "
                               "through the firmware compensator.</p>",
                               calib::FormatNumber(spec.accel_mg),
                               calib::FormatNumber(spec.body_rate_dps)),
                   body);
}

}  // namespace adahrs::proving
