#include "calib/report/acceptance_section.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "calib/report/html_builder.h"
#include "calib/report/svg_plot.h"

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

constexpr int kFigureWidthPx = 400;
constexpr int kFigureHeightPx = 260;
constexpr const char* kLimitColour = "#1f77b4";

std::string UpAxisText(int orientation) {
  return fmt::format(
      "{}{} up", orientation % 10 == 1 ? "+" : "-", "xyz"[(orientation / 10 - 1) % 3]);
}

// A band of +-half_width(x) at each x of `xs` (sorted, distinct).
PlotBand Band(const std::string& label,
              const std::vector<double>& xs,
              const std::vector<double>& half_width,
              const std::string& colour) {
  PlotBand band{label, xs, {}, {}, colour};
  for (double w : half_width) {
    band.y_lo.push_back(-w);
    band.y_hi.push_back(w);
  }
  return band;
}

// The error of one family's points against `x_of` (a point series per axis), the tolerance band
// over the points' x range and, when the points carry one, the physical limit's band.
Plot ErrorFigure(const std::string& title,
                 const std::string& x_label,
                 const std::string& figure,
                 const std::vector<const AcceptancePoint*>& points,
                 double (*x_of)(const AcceptancePoint&)) {
  Plot plot{title,
            x_label,
            fmt::format("error: measured - reference ({})", points.front()->unit),
            {},
            {}};
  plot.figure = figure;
  plot.width_px = kFigureWidthPx;
  plot.height_px = kFigureHeightPx;
  std::map<std::string, PlotSeries> by_quantity;
  std::map<double, double> tolerance, limit;  // by x: the largest
  for (const AcceptancePoint* p : points) {
    PlotSeries& s = by_quantity[p->quantity];
    s.label = p->quantity;
    s.style = PlotSeries::Style::kPoints;
    const double x = x_of(*p);
    s.x.push_back(x);
    s.y.push_back(p->error);
    tolerance[x] = std::max(tolerance[x], p->tolerance);
    if (p->physical_limit) limit[x] = std::max(limit[x], *p->physical_limit);
  }
  std::vector<double> xs, tol;
  for (const auto& [x, t] : tolerance) {
    xs.push_back(x);
    tol.push_back(t);
  }
  if (xs.size() == 1) {  // a band needs a width: +-1 about the one x
    xs = {xs[0] - 1.0, xs[0] + 1.0};
    tol = {tol[0], tol[0]};
  }
  if (limit.size() == tolerance.size() && limit.size() > 1) {
    std::vector<double> lx, lw;
    for (const auto& [x, w] : limit) {
      lx.push_back(x);
      lw.push_back(w);
    }
    plot.bands.push_back(
        Band("physical limit (noise and bias wander, 3 sigma)", lx, lw, kLimitColour));
  }
  plot.bands.push_back(Band("specification tolerance (+-)", xs, tol, "#2ca02c"));
  for (auto& [q, s] : by_quantity) plot.series.push_back(std::move(s));
  return plot;
}

double ChamberOf(const AcceptancePoint& p) { return p.chamber_c; }
double RateOf(const AcceptancePoint& p) { return p.rate_dps.value_or(0.0); }

// The reference method's acceptance figures (Figs. 66-68) for an IMU: per orientation the
// acceleration error against chamber temperature and the body-rate error against the commanded
// rate, then the thermal profile's per-bin errors with the standard deviations judged.
std::string ImuAcceptanceFigures(const UnitAcceptance& u) {
  std::map<int, std::vector<const AcceptancePoint*>> accel, rate;
  std::vector<const AcceptancePoint*> thermal_accel, thermal_rate, stability;
  for (const AcceptancePoint& p : u.points) {
    const std::string family = QuantityFamily(p.quantity);
    const bool thermal = p.kind == "thermal_profile";
    if (family == "acceleration") (thermal ? thermal_accel : accel[p.orientation]).push_back(&p);
    if (family == "body_rate") {
      if (thermal) {
        thermal_rate.push_back(&p);
      } else if (p.rate_dps) {
        rate[p.orientation].push_back(&p);
      }
    }
    if (family.starts_with("thermal_") && family.ends_with("_std")) stability.push_back(&p);
  }
  std::string html = "<div class=\"figures\">\n";
  for (const auto& [orientation, points] : accel) {
    html += RenderSvg(ErrorFigure(fmt::format("{} acceleration error, orientation {} ({})",
                                              u.serial,
                                              orientation,
                                              UpAxisText(orientation)),
                                  "chamber temperature (degC)",
                                  "acceptance-accel",
                                  points,
                                  ChamberOf));
  }
  for (const auto& [orientation, points] : rate) {
    html += RenderSvg(ErrorFigure(fmt::format("{} body-rate error, orientation {} ({})",
                                              u.serial,
                                              orientation,
                                              UpAxisText(orientation)),
                                  "commanded table rate about the up axis (deg/s)",
                                  "acceptance-rate",
                                  points,
                                  RateOf));
  }
  for (const bool is_rate : {false, true}) {
    const auto& points = is_rate ? thermal_rate : thermal_accel;
    if (points.empty()) continue;
    std::string judged;
    double limit = 0.0;
    for (const AcceptancePoint* p : stability) {
      if ((p->unit == "deg/s") != is_rate) continue;
      judged += fmt::format("{}{} {} ({})",
                            judged.empty() ? "" : ", ",
                            p->quantity.back(),
                            FormatNumber(p->measured, 2),
                            OutcomeText(p->outcome()));
      limit = p->tolerance;
    }
    const std::string title =
        fmt::format("{} thermal acceptance: {}", u.serial, is_rate ? "body rate" : "acceleration");
    Plot plot =
        ErrorFigure(title, "chamber temperature (degC)", "acceptance-thermal", points, ChamberOf);
    plot.y_label = fmt::format("mean error per 5 degC bin ({})", points.front()->unit);
    for (PlotSeries& s : plot.series) s.style = PlotSeries::Style::kLine;
    html += RenderSvg(plot);
    if (!judged.empty()) {
      html += fmt::format(
          "<p class=\"note\">{}: standard deviation of the error's 1 s means over the profile, "
          "per axis {} {} (limit {}).</p>\n",
          XmlEscape(title),
          XmlEscape(judged),
          is_rate ? "deg/s" : "mg",
          FormatNumber(limit, 3));
    }
  }
  return html + "</div>\n";
}

}  // namespace

std::string AcceptanceSectionBody(const std::vector<AcceptanceFile>& files) {
  std::string html;
  for (const AcceptanceFile& f : files) {
    html += RenderTable(SummaryTable(f));
    html += RenderTable(WorstMarginTable(f.unit));
    if (f.unit.kind == "imu" && !f.unit.points.empty()) html += ImuAcceptanceFigures(f.unit);
    html += RenderTable(PointsTable(f));
  }
  return html;
}

}  // namespace adahrs::calib
