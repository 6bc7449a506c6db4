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
#include "calib/ads_calibration/unit_hysteresis_operator.h"
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
// Where the calibration's bridge history starts its thermal operators (bridge_history.cc).
constexpr double kRoomTemperatureC = 25.0;

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
                      const std::string& source) {
  const Specification spec = Specification::Reference();
  const ToleranceTable& tol = altitude ? spec.altitude_ft : spec.airspeed_kt;
  Plot plot{
      fmt::format("{} {} error by chamber temperature", serial, altitude ? "altitude" : "airspeed"),
      altitude ? "pressure altitude from the test set's Ps, ISA (ft)"
               : "calibrated airspeed from the test set's Qc (kt)",
      altitude ? "altitude error (ft)" : "airspeed error (kt)",
      {},
      {}};
  plot.figure = "ads-error";
  PlotBand band{"specification tolerance (+-)", {}, {}, {}};
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
std::string RawDataPlots(const std::string& serial, const std::vector<Acquisition>& points) {
  std::string html;
  for (const bool pitot : {false, true}) {
    std::vector<std::pair<double, double>> xy;  // kPa, code
    for (const Acquisition& a : points) {
      if (a.n_raw > 0)
        xy.push_back({(pitot ? a.qc_ref_pa : a.ps_ref_pa) / 1000.0, pitot ? a.pt_cnt : a.ps_cnt});
    }
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
    for (const Acquisition& a : points) {
      if (a.n_raw == 0) continue;
      const double bin = TemperatureBin(a.raw_temp_c);
      const double x = (pitot ? a.qc_ref_pa : a.ps_ref_pa) / 1000.0;
      const double code = pitot ? a.pt_cnt : a.ps_cnt;
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

// The pressure the unit's hysteresis operator of `surface` is driven by, at an acquisition: the
// surface's z before its law (static or impact pressure in Pa under the ISA or CAS law, else the
// altitude or airspeed itself), here the test set's, as the fit models it.
double OperatorInput(const fm::SurfaceFit& surface, bool altitude, const Acquisition& a) {
  switch (surface.law) {
    case fm::SurfaceLaw::kIsaAltitude:
      return a.ps_ref_pa;
    case fm::SurfaceLaw::kCas:
      return a.qc_ref_pa;
    case fm::SurfaceLaw::kDirect:
      break;
  }
  return altitude ? a.alt_ref_ft : a.cas_ref_kt;
}

// One surface's pressure and thermal operators (off when their span is 0), virgin at sea level,
// zero airspeed and 25 degC, as the calibration's bridge history starts (bridge_history.h).
class SurfaceStates {
 public:
  SurfaceStates(const fm::SurfaceFit& surface, bool altitude)
      : surface_(surface), altitude_(altitude) {
    const fm::HysteresisCompensation& h = surface.hysteresis;
    if (h.pressure_span > 0.0) pressure_.emplace(h.pressure_span);
    if (h.thermal_span_c > 0.0) thermal_.emplace(h.thermal_span_c);
    Acquisition start;
    start.ps_ref_pa = common::kIsaSeaLevelPressure_pa;
    start.alt_ref_ft = common::IsaPressureAltitudeFt(start.ps_ref_pa);
    if (pressure_) pressure_->Update(OperatorInput(surface_, altitude_, start));
    if (thermal_) thermal_->Update(kRoomTemperatureC);
  }
  /// The surface's output at the acquisition's mean codes, its operators advanced to it.
  double Output(const Acquisition& a, double x_code, double y_code) {
    const double s_p = pressure_ ? pressure_->Update(OperatorInput(surface_, altitude_, a)) : 0.0;
    const double s_t = thermal_ ? thermal_->Update(a.raw_temp_c) : 0.0;
    return fm::SurfaceOutput(surface_, x_code, y_code, s_p, s_t);
  }

 private:
  const fm::SurfaceFit& surface_;
  bool altitude_;
  std::optional<UnitHysteresisOperator> pressure_, thermal_;
};

// Where the fitted surface misses: each acquisition at (chamber temperature, reference input),
// coloured by |residual| / tolerance. The altitude map takes the acquisitions below the airspeed
// range (the static sweeps), the airspeed map those inside it.
std::string ResidualMap(const std::string& serial,
                        const std::vector<Acquisition>& points,
                        bool altitude) {
  const Specification spec = Specification::Reference();
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
                                           const ConstantsFile* constants)
    : serial_(std::move(serial)), meta_(std::move(meta)), constants_(constants) {}

void AdsReportAccumulator::Add(const hil::AdsRecordRow& row) {
  if (row.unit != serial_ || row.tag == 0 || Rejected(meta_, row.step, row.t_s)) return;
  Acquisition& a =
      groups_[{row.step, row.tag, std::lround(row.ps_ref_pa), std::lround(row.qc_ref_pa)}];
  if (row.alt_ft && row.cas_kt) {
    a.alt_ref_ft += common::IsaPressureAltitudeFt(row.ps_ref_pa);
    a.cas_ref_kt += row.qc_ref_pa > 0.0 ? common::CalibratedAirspeedKt(row.qc_ref_pa) : 0.0;
    a.temp_c += row.chamber_c;
    a.alt_ft += *row.alt_ft;
    a.cas_kt += *row.cas_kt;
    ++a.n;
    unit_values_ = true;
    return;
  }
  a.ps_ref_pa += row.ps_ref_pa;
  a.qc_ref_pa += row.qc_ref_pa;
  a.ps_cnt += row.ps_cnt;
  a.pt_cnt += row.pt_cnt;
  a.ps_bridge_cnt += row.ps_temp_cnt;
  a.pt_bridge_cnt += row.pt_temp_cnt;
  a.raw_temp_c += row.chamber_c;
  ++a.n_raw;
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
  // Means, in step order (the groups' key begins with the step). Raw acquisitions are evaluated
  // with the constants at their mean codes, the surfaces' hysteresis operators driven through
  // them in that order, as the fit models the bridges' states.
  std::vector<Acquisition> points;
  std::optional<SurfaceStates> altitude_states, airspeed_states;
  if (constants_ != nullptr) {
    altitude_states.emplace(constants_->ads->altitude_ft, true);
    airspeed_states.emplace(constants_->ads->airspeed_kt, false);
  }
  bool reference_values = false;
  for (Acquisition a : groups_ | std::views::values) {
    if (a.n > 0) {
      for (double* v : {&a.alt_ref_ft, &a.cas_ref_kt, &a.temp_c, &a.alt_ft, &a.cas_kt}) *v /= a.n;
    }
    if (a.n_raw > 0) {
      for (double* v : {&a.ps_ref_pa,
                        &a.qc_ref_pa,
                        &a.ps_cnt,
                        &a.pt_cnt,
                        &a.ps_bridge_cnt,
                        &a.pt_bridge_cnt,
                        &a.raw_temp_c}) {
        *v /= a.n_raw;
      }
      if (a.n == 0 && constants_ != nullptr) {
        a.alt_ref_ft = common::IsaPressureAltitudeFt(a.ps_ref_pa);
        a.cas_ref_kt = a.qc_ref_pa > 0.0 ? common::CalibratedAirspeedKt(a.qc_ref_pa) : 0.0;
        a.temp_c = a.raw_temp_c;
        a.alt_ft = altitude_states->Output(a, a.ps_cnt, a.ps_bridge_cnt);
        a.cas_kt = airspeed_states->Output(a, a.pt_cnt, a.pt_bridge_cnt);
        a.n = a.n_raw;
        reference_values = true;
      }
    }
    points.push_back(a);
  }
  const bool raw_rows =
      std::any_of(points.begin(), points.end(), [](const Acquisition& a) { return a.n_raw > 0; });
  if (raw_rows) {
    html += Section(serial_ + "-raw",
                    3,
                    serial_ + " raw data: bridge codes against the test set's pressures",
                    RawDataPlots(serial_, points));
  }
  std::vector<Acquisition> judged;
  for (const Acquisition& a : points) {
    if (a.n > 0) judged.push_back(a);
  }
  std::string map;
  if (judged.empty()) {
    map = NotAvailable("ADS error map",
                       constants_ == nullptr ? "raw rows only and no constants.json for " + serial_
                                             : "no tagged acquisition rows for " + serial_);
  } else {
    const std::string source = unit_values_ && reference_values
                                   ? "unit output and reference compensator"
                               : unit_values_ ? "the unit's own surface output"
                                              : "reference compensator on mean raw codes";
    if (reference_values) {
      map += "<div class=\"figures\">\n" + ResidualMap(serial_, judged, true) +
             ResidualMap(serial_, judged, false) + "</div>\n";
    }
    map += ErrorPlot(serial_, judged, true, source) + ErrorPlot(serial_, judged, false, source);
  }
  return html +
         Section(
             serial_ + "-error-map", 3, serial_ + " error map against the tolerance envelope", map);
}

std::string AdsReportSections(const std::string& serial,
                              const std::vector<hil::AdsRecordRow>& rows,
                              const hil::RecordingMeta& meta,
                              const ConstantsFile* constants) {
  AdsReportAccumulator accumulator(serial, meta, constants);
  for (const hil::AdsRecordRow& row : rows) accumulator.Add(row);
  return accumulator.Sections();
}

}  // namespace adahrs::calib
