#include "calib/report/ads_report_sections.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <ranges>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "calib/acceptance/specification.h"
#include "calib/ads_calibration/bridge_history.h"
#include "calib/report/constants_table.h"
#include "calib/report/html_builder.h"
#include "calib/report/svg_plot.h"
#include "common/air_data.h"
#include "common/atmosphere.h"
#include "firmware_model/reference_compensator.h"

namespace adahrs::calib {
namespace {

namespace fm = firmware_model;

// Chamber temperatures are grouped to this width for the map's series.
constexpr double kTemperatureBinC = 5.0;

// A chamber temperature's 5 degC bin (never "-0").
double TemperatureBin(double temp_c) {
  return std::round(temp_c / kTemperatureBinC) * kTemperatureBinC + 0.0;
}

using Acquisition = AdsReportAccumulator::Acquisition;

bool Rejected(const hil::RecordingMeta& meta, int step, double t_s) {
  for (const hil::RejectedInterval& r : meta.rejected_intervals) {
    if (r.step == step && t_s >= r.t_start_s && t_s <= r.t_end_s) return true;
  }
  return false;
}

std::string ErrorPlot(const std::string& serial,
                      const std::vector<Acquisition>& points,
                      bool altitude,
                      const std::string& source,
                      const Specification& spec) {
  const ToleranceTable& tol = altitude ? spec.altitude_ft : spec.airspeed_kt;
  Plot plot{
      fmt::format("{} {} error by chamber temperature", serial, altitude ? "altitude" : "airspeed"),
      altitude ? "pressure altitude from the test set's Ps, ISA (ft)"
               : "calibrated airspeed from the test set's Qc (kt)",
      altitude ? "altitude error (ft)" : "airspeed error (kt)",
      {},
      {}};
  plot.figure = "ads-error";
  PlotBand band{spec.name + " tolerance (+-)", {}, {}, {}};
  const int samples = 60;
  for (int i = 0; i <= samples; ++i) {
    const double x = tol.input_min() + (tol.input_max() - tol.input_min()) * i / samples;
    band.x.push_back(x);
    band.y_lo.push_back(-tol.At(x));
    band.y_hi.push_back(tol.At(x));
  }
  plot.bands.push_back(band);
  std::map<double, PlotSeries> by_temp;
  HtmlTable table{
      fmt::format("{} {} error per acquisition", serial, altitude ? "altitude" : "airspeed"),
      {"chamber (degC)",
       altitude ? "reference (ft)" : "reference (kt)",
       altitude ? "error (ft)" : "error (kt)",
       "tolerance",
       "verdict"},
      {}};
  for (const Acquisition& a : points) {
    const double x = altitude ? a.alt_ref_ft : a.cas_ref_kt;
    if (x < tol.input_min() || x > tol.input_max()) continue;
    const double error = altitude ? a.alt_ft - a.alt_ref_ft : a.cas_kt - a.cas_ref_kt;
    const double bin = TemperatureBin(a.temp_c);
    PlotSeries& s = by_temp[bin];
    s.label = fmt::format("{:g} degC", bin);
    s.style = PlotSeries::Style::kPoints;
    s.x.push_back(x);
    s.y.push_back(error);
    table.rows.push_back({FormatNumber(a.temp_c, 4),
                          FormatNumber(x, 6),
                          FormatNumber(error, 3),
                          FormatNumber(tol.At(x), 3),
                          std::abs(error) <= tol.At(x) ? "PASS" : "FAIL"});
  }
  if (by_temp.empty()) {
    return NotAvailable(std::string(altitude ? "Altitude" : "Airspeed") + " error map",
                        "no acquisition inside the operating range");
  }
  for (auto& [bin, s] : by_temp) plot.series.push_back(std::move(s));
  return RenderSvg(plot) + "<p class=\"note\">" + XmlEscape(plot.title) + ": the values are " +
         XmlEscape(source) + ".</p>\n" + RenderTable(table);
}

// Each bridge's mean code against the test set's pressure, a series per chamber temperature; then
// the same codes less the least-squares line through all of them, which shows what the full-scale
// view hides: the shift with temperature and the span's curvature (the reference's Fig. 16).
std::string RawDataPlots(const std::string& serial,
                         const std::vector<AdsCalibrationPoint>& points) {
  std::string html;
  for (const bool pitot : {false, true}) {
    std::vector<std::pair<double, double>> xy;  // kPa, code
    for (const AdsCalibrationPoint& p : points)
      xy.push_back({(pitot ? p.qc_ref_pa : p.ps_ref_pa) / 1000.0, pitot ? p.pt_cnt : p.ps_cnt});
    if (xy.size() < 2) return "";
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const auto& [x, y] : xy) {
      sx += x;
      sy += y;
      sxx += x * x;
      sxy += x * y;
    }
    const double n = static_cast<double>(xy.size());
    const double det = n * sxx - sx * sx;
    const double slope = det != 0.0 ? (n * sxy - sx * sy) / det : 0.0;
    const double intercept = (sy - slope * sx) / n;
    const std::string bridge = pitot ? "pitot" : "static";
    const std::string x_label = pitot ? "impact pressure Qc from the test set (kPa)"
                                      : "static pressure Ps from the test set (kPa)";
    Plot plot{fmt::format("{} {} bridge: raw code against the test set's {} pressure",
                          serial,
                          bridge,
                          pitot ? "impact" : "static"),
              x_label,
              fmt::format("{} bridge output (ADS1254 code)", bridge),
              {},
              {}};
    Plot deviation{fmt::format("{} {} bridge: raw code less its straight line", serial, bridge),
                   x_label,
                   fmt::format("code - ({:.6g} + {:.6g} x kPa) (ADS1254 code)", intercept, slope),
                   {},
                   {}};
    plot.figure = deviation.figure = "ads-raw";
    std::map<double, PlotSeries> by_temp, dev_by_temp;
    for (const AdsCalibrationPoint& p : points) {
      const double bin = TemperatureBin(p.chamber_c);
      const double x = (pitot ? p.qc_ref_pa : p.ps_ref_pa) / 1000.0;
      const double code = pitot ? p.pt_cnt : p.ps_cnt;
      for (auto* m : {&by_temp, &dev_by_temp}) {
        PlotSeries& s = (*m)[bin];
        s.label = fmt::format("{:g} degC", bin);
        s.style = PlotSeries::Style::kPoints;
        s.x.push_back(x);
        s.y.push_back(m == &by_temp ? code : code - (intercept + slope * x));
      }
    }
    for (auto& [bin, s] : by_temp) plot.series.push_back(std::move(s));
    for (auto& [bin, s] : dev_by_temp) deviation.series.push_back(std::move(s));
    html += RenderSvg(plot) + RenderSvg(deviation);
  }
  return html;
}

// The calibration points as the constants give them: each at its mean codes, with the states the
// fit regresses on (pressure-driven, bridge_history.h: the z of the ISA and CAS laws every strategy
// writes hysteresis terms under).
std::vector<Acquisition> Evaluated(const std::vector<AdsCalibrationPoint>& points,
                                   const fm::AdsCalibrationConstants& c) {
  const std::vector<PointHistory> history = BridgeHistoryOf(points, HysteresisSpans::Of(c));
  std::vector<Acquisition> out;
  for (size_t i = 0; i < points.size(); ++i) {
    const AdsCalibrationPoint& p = points[i];
    const PointHistory& h = history[i];
    out.push_back({p.alt_ft,
                   p.cas_kt,
                   p.chamber_c,
                   fm::SurfaceOutput(c.altitude_ft,
                                     p.ps_cnt,
                                     p.ps_temp_cnt,
                                     h.static_bridge.s_pressure,
                                     h.static_bridge.s_thermal),
                   fm::SurfaceOutput(c.airspeed_kt,
                                     p.pt_cnt,
                                     p.pt_temp_cnt,
                                     h.pitot_bridge.s_pressure,
                                     h.pitot_bridge.s_thermal),
                   p.rows});
  }
  return out;
}

// Where the fitted surface misses: each acquisition at (chamber temperature, reference input),
// coloured by |residual| / tolerance. The altitude map takes the acquisitions below the airspeed
// range (the static sweeps), the airspeed map those inside it.
std::string ResidualMap(const std::string& serial,
                        const std::vector<Acquisition>& points,
                        bool altitude,
                        const Specification& spec) {
  const ToleranceTable& tol = altitude ? spec.altitude_ft : spec.airspeed_kt;
  const double cas_min_kt = spec.airspeed_kt.input_min();
  Plot plot{fmt::format("{} {} surface residual map against the tolerance",
                        serial,
                        altitude ? "altitude" : "airspeed"),
            "chamber temperature (degC)",
            altitude ? "pressure altitude from the test set's Ps, ISA (ft)"
                     : "calibrated airspeed from the test set's Qc (kt)",
            {},
            {}};
  plot.figure = "ads-surface-residual";
  std::array<PlotSeries, 4> classes = {
      PlotSeries{"|residual| <= 1/4 tolerance", {}, {}, PlotSeries::Style::kPoints, "#2ca02c"},
      PlotSeries{
          "1/4 < |residual| / tolerance <= 1/2", {}, {}, PlotSeries::Style::kPoints, "#bcbd22"},
      PlotSeries{
          "1/2 < |residual| / tolerance <= 1", {}, {}, PlotSeries::Style::kPoints, "#ff7f0e"},
      PlotSeries{"|residual| > tolerance", {}, {}, PlotSeries::Style::kPoints, "#d62728"}};
  for (const Acquisition& a : points) {
    if (a.n == 0 || (a.cas_ref_kt >= cas_min_kt) == altitude) continue;
    const double x = altitude ? a.alt_ref_ft : a.cas_ref_kt;
    if (x < tol.input_min() || x > tol.input_max()) continue;
    const double ratio =
        std::abs(altitude ? a.alt_ft - a.alt_ref_ft : a.cas_kt - a.cas_ref_kt) / tol.At(x);
    PlotSeries& s = classes[ratio <= 0.25 ? 0 : ratio <= 0.5 ? 1 : ratio <= 1.0 ? 2 : 3];
    s.x.push_back(a.temp_c);
    s.y.push_back(x);
  }
  for (PlotSeries& s : classes) {
    if (!s.x.empty()) plot.series.push_back(std::move(s));
  }
  return plot.series.empty() ? "" : RenderSvg(plot);
}

}  // namespace

AdsReportAccumulator::AdsReportAccumulator(std::string serial,
                                           hil::RecordingMeta meta,
                                           const ConstantsFile* constants,
                                           std::string source,
                                           Specification spec)
    : serial_(std::move(serial)),
      meta_(std::move(meta)),
      constants_(constants),
      spec_(std::move(spec)),
      raw_points_(meta_, serial_, std::move(source)) {}

void AdsReportAccumulator::Add(const hil::AdsRecordRow& row, int line) {
  if (row.unit != serial_) return;
  if (!row.alt_ft || !row.cas_kt) {
    raw_rows_ = true;
    if (raw_refused_.empty()) {
      try {
        raw_points_.Add(row, line);
      } catch (const std::runtime_error& e) {
        raw_refused_ = e.what();  // as the fit would refuse the run
      }
    }
    return;
  }
  if (row.tag == 0 || Rejected(meta_, row.step, row.t_s)) return;
  Acquisition& a =
      groups_[{row.step, row.tag, std::lround(row.ps_ref_pa), std::lround(row.qc_ref_pa)}];
  a.alt_ref_ft += common::IsaPressureAltitudeFt(row.ps_ref_pa);
  a.cas_ref_kt += row.qc_ref_pa > 0.0 ? common::CalibratedAirspeedKt(row.qc_ref_pa) : 0.0;
  a.temp_c += row.chamber_c;
  a.alt_ft += *row.alt_ft;
  a.cas_kt += *row.cas_kt;
  ++a.n;
}

// The raw rows' calibration points, or why there are none (the selection's refusal).
std::vector<AdsCalibrationPoint> AdsReportAccumulator::RawPoints(std::string* why) const {
  if (!raw_rows_) return {};
  if (!raw_refused_.empty()) {
    *why = raw_refused_;
    return {};
  }
  try {
    return raw_points_.Points();
  } catch (const std::runtime_error& e) {
    *why = e.what();
    return {};
  }
}

std::string AdsReportAccumulator::Sections() const {
  std::string html =
      Section(serial_ + "-constants",
              3,
              serial_ + " constants",
              constants_ != nullptr ? ConstantsSection(*constants_)
                                    : NotAvailable("Constants",
                                                   "no constants.json for " + serial_ +
                                                       " in the fit "
                                                       "directory"));
  std::string raw_why;
  const std::vector<AdsCalibrationPoint> raw = RawPoints(&raw_why);
  if (raw_rows_) {
    html +=
        Section(serial_ + "-raw",
                3,
                serial_ + " raw data: bridge codes against the test set's pressures",
                raw.empty() ? NotAvailable("ADS raw data", raw_why) : RawDataPlots(serial_, raw));
  }
  std::vector<Acquisition> judged;
  for (Acquisition a : groups_ | std::views::values) {
    for (double* v : {&a.alt_ref_ft, &a.cas_ref_kt, &a.temp_c, &a.alt_ft, &a.cas_kt}) *v /= a.n;
    judged.push_back(a);
  }
  const bool unit_values = !judged.empty();
  const bool reference_values = constants_ != nullptr && !raw.empty();
  if (reference_values) {
    const std::vector<Acquisition> evaluated = Evaluated(raw, *constants_->ads);
    judged.insert(judged.end(), evaluated.begin(), evaluated.end());
  }
  std::string map;
  if (judged.empty()) {
    map = NotAvailable("ADS error map",
                       constants_ == nullptr ? "raw rows only and no constants.json for " + serial_
                       : !raw_why.empty()    ? raw_why
                                             : "no tagged acquisition rows for " + serial_);
  } else {
    const std::string source = unit_values && reference_values
                                   ? "unit output and reference compensator"
                               : unit_values ? "the unit's own surface output"
                                             : "reference compensator on the calibration points";
    if (reference_values) {
      map += "<div class=\"figures\">\n" + ResidualMap(serial_, judged, true, spec_) +
             ResidualMap(serial_, judged, false, spec_) + "</div>\n";
    }
    map += ErrorPlot(serial_, judged, true, source, spec_) +
           ErrorPlot(serial_, judged, false, source, spec_);
  }
  return html +
         Section(
             serial_ + "-error-map", 3, serial_ + " error map against the tolerance envelope", map);
}

}  // namespace adahrs::calib
