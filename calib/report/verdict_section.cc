#include "calib/report/verdict_section.h"

#include <set>

#include <fmt/format.h>

#include "calib/report/html_builder.h"
#include "calib/report/svg_plot.h"

namespace adahrs::calib {
namespace {

// "acceleration +0.49 mg at step 16: accel_y at orientation 11, 30.6 degC", one per quantity.
std::string WorstMargins(const UnitAcceptance& u) {
  std::string text;
  for (const WorstMargin& w : u.WorstMargins()) {
    text += fmt::format("{}{} {:+.3g} {} at step {}: {}",
                        text.empty() ? "" : "; ",
                        w.quantity,
                        w.margin,
                        w.unit,
                        w.step,
                        w.point);
  }
  return text;
}

std::string Specifications(const std::vector<AcceptanceFile>& files) {
  std::set<std::string> seen;
  std::string text;
  for (const AcceptanceFile& f : files) {
    const AcceptanceFileSpecification& s = f.specification_id;
    const std::string one =
        s.sha256.empty() ? std::string("not recorded in the acceptance file")
                         : fmt::format("{} version {}, SHA-256 {}", s.name, s.version, s.sha256);
    if (seen.insert(one).second) text += (text.empty() ? "" : "; ") + one;
  }
  return text;
}

// The thermal acceptance on page one: per unit with thermal stability points, the largest standard
// deviation of each family against its limit and the outcome of the pair; empty without any.
std::string ThermalAcceptance(const std::vector<AcceptanceFile>& files) {
  HtmlTable table{
      "Thermal acceptance (reference section 4.2.5): the largest standard deviation of the error's "
      "1 s means over the logged thermal profile, per body axis",
      {"unit", "outcome", "body rate (deg/s)", "limit (deg/s)", "acceleration (mg)", "limit (mg)"},
      {}};
  for (const AcceptanceFile& f : files) {
    const AcceptancePoint* largest[2] = {nullptr, nullptr};  // rate, acceleration
    Outcome outcome = Outcome::kPass;
    for (const AcceptancePoint& p : f.unit.points) {
      const std::string family = QuantityFamily(p.quantity);
      const int k = family == "thermal_body_rate_std"      ? 0
                    : family == "thermal_acceleration_std" ? 1
                                                           : -1;
      if (k < 0) continue;
      if (largest[k] == nullptr || p.measured > largest[k]->measured) largest[k] = &p;
      if (p.outcome() == Outcome::kFail ||
          (p.outcome() == Outcome::kMarginal && outcome == Outcome::kPass)) {
        outcome = p.outcome();
      }
    }
    if (largest[0] == nullptr && largest[1] == nullptr) continue;
    std::vector<std::string> row = {f.unit.serial, OutcomeText(outcome)};
    for (const AcceptancePoint* p : largest) {
      row.push_back(p ? fmt::format("{} ({})", FormatNumber(p->measured, 3), p->quantity.back())
                      : "not judged");
      row.push_back(p ? FormatNumber(p->tolerance, 3) : "");
    }
    table.rows.push_back(row);
  }
  return table.rows.empty() ? "" : RenderTable(table);
}

}  // namespace

std::string VerdictSectionBody(const std::vector<AcceptanceFile>& files,
                               const std::string& sequence_name) {
  if (files.empty()) {
    return "<p>Not judged: no acceptance.json for this run (" + XmlEscape(sequence_name) +
           "). A calibration run is judged through the acceptance run of the constants it gave "
           "(its report), or with adahrs acceptance --run on this run.</p>\n";
  }
  HtmlTable table{
      "Acceptance outcome per unit (worst margin = tolerance - |error|; negative fails)",
      {"unit",
       "kind",
       "outcome",
       "points failed",
       "points marginal",
       "points judged",
       "worst margin per quantity"},
      {}};
  int failed_units = 0;
  for (const AcceptanceFile& f : files) {
    const UnitAcceptance& u = f.unit;
    const Outcome outcome = u.outcome();
    failed_units += outcome == Outcome::kFail ? 1 : 0;
    table.rows.push_back({u.serial,
                          u.kind,
                          OutcomeText(outcome),
                          std::to_string(u.failed()),
                          std::to_string(u.marginal()),
                          std::to_string(u.points.size()),
                          WorstMargins(u)});
  }
  return fmt::format("<p class=\"verdict\">{} of {} unit(s) accepted (PASS or MARGINAL).</p>\n",
                     files.size() - static_cast<size_t>(failed_units),
                     files.size()) +
         RenderTable(table) + ThermalAcceptance(files) +
         "<p>Specification: " + XmlEscape(Specifications(files)) + "</p>\n";
}

}  // namespace adahrs::calib
