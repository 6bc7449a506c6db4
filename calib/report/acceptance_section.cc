#include "calib/report/acceptance_section.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "calib/report/html_builder.h"

namespace adahrs::calib {
namespace {

// "outside specification: 3; within specification: 60": the body-rate points per verdict, in the
// order of the verdicts' words.
std::string RateVerdictCounts(const UnitAcceptance& unit) {
  std::vector<std::pair<std::string, int>> counts;
  for (PointVerdict v : {PointVerdict::kWithinSpecification,
                         PointVerdict::kWithinPhysicalLimit,
                         PointVerdict::kOutsideBoth,
                         PointVerdict::kOutsideSpecification}) {
    if (const int n = unit.Count("body_rate", v); n > 0) counts.push_back({PointVerdictText(v), n});
  }
  std::sort(counts.begin(), counts.end());
  std::string text;
  for (const auto& [verdict, n] : counts) {
    text += fmt::format("{}{}: {}", text.empty() ? "" : "; ", verdict, n);
  }
  return text;
}

HtmlTable SummaryTable(const AcceptanceFile& f) {
  const UnitAcceptance& u = f.unit;
  HtmlTable summary{fmt::format("{}: acceptance verdict", u.serial), {"item", "value"}, {}};
  summary.rows.push_back({"run id", f.run.run_id});
  summary.rows.push_back({"recording sha256", f.run.recording_sha256});
  summary.rows.push_back({"mode", std::to_string(u.mode)});
  summary.rows.push_back({"points failed", fmt::format("{} of {}", u.failed(), u.points.size())});
  summary.rows.push_back({"verdict", OutcomeText(u.outcome())});
  if (const std::string counts = RateVerdictCounts(u); !counts.empty()) {
    summary.rows.push_back({"body-rate points", counts});
  }
  if (f.physical_limit) {
    summary.rows.push_back(
        {"physical limit",
         fmt::format("point noise and bias wander over {:g} h since calibration, from "
                     "a {:.0f} s rest record at {:.1f} degC",
                     f.physical_limit->since_calibration_h,
                     f.physical_limit->rest_record_s,
                     f.physical_limit->rest_chamber_c)});
  }
  return summary;
}

}  // namespace

HtmlTable WorstMarginTable(const UnitAcceptance& unit) {
  HtmlTable worst{fmt::format("{}: worst margin per quantity (tolerance - |error|)", unit.serial),
                  {"quantity", "margin", "unit", "step", "point", "verdict"},
                  {}};
  for (const WorstMargin& w : unit.WorstMargins()) {
    worst.rows.push_back({w.quantity,
                          FormatNumber(w.margin, 4),
                          w.unit,
                          std::to_string(w.step),
                          w.point,
                          w.margin >= 0.0 ? "PASS" : "FAIL"});
  }
  return worst;
}

namespace {

HtmlTable PointsTable(const AcceptanceFile& f) {
  HtmlTable points{fmt::format("{}: acceptance points (mean over the step's packets; noise 1 "
                               "sigma; physical limit 3 sigma)",
                               f.unit.serial),
                   {"step",
                    "kind",
                    "quantity",
                    "condition",
                    "measured",
                    "reference",
                    "error",
                    "noise",
                    "tolerance",
                    "physical limit",
                    "margin",
                    "unit",
                    "verdict",
                    "against specification and physical limit"},
                   {}};
  for (const AcceptancePoint& p : f.unit.points) {
    points.rows.push_back({std::to_string(p.step),
                           p.kind,
                           p.quantity,
                           p.Condition(),
                           FormatNumber(p.measured, 8),
                           FormatNumber(p.reference, 8),
                           FormatNumber(p.error, 4),
                           FormatNumber(p.noise, 3),
                           FormatNumber(p.tolerance, 4),
                           p.physical_limit ? FormatNumber(*p.physical_limit, 4) : "",
                           FormatNumber(p.tolerance - std::abs(p.error), 4),
                           p.unit,
                           p.pass ? "PASS" : "FAIL",
                           PointVerdictText(p.verdict())});
  }
  return points;
}

}  // namespace

std::string AcceptanceSectionBody(const std::vector<AcceptanceFile>& files) {
  std::string html;
  for (const AcceptanceFile& f : files) {
    html += RenderTable(SummaryTable(f));
    html += RenderTable(WorstMarginTable(f.unit));
    html += RenderTable(PointsTable(f));
  }
  return html;
}

}  // namespace adahrs::calib
