#include "calib/report/ads_report_sections.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <ranges>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "calib/acceptance/specification.h"
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
  Plot plot{fmt::format("{} {} error vs {} by chamber temperature ({})",
                        serial,
                        altitude ? "altitude" : "airspeed",
                        altitude ? "altitude" : "airspeed",
                        source),
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
    const double bin = std::round(a.temp_c / kTemperatureBinC) * kTemperatureBinC;
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
  return RenderSvg(plot) + RenderTable(table);
}

// Each bridge's mean code against the test set's pressure, a series per chamber temperature.
std::string RawDataPlots(const std::string& serial, const std::vector<Acquisition>& points) {
  std::string html;
  for (const bool pitot : {false, true}) {
    Plot plot{fmt::format("{} {} bridge: raw code against the test set's {} pressure",
                          serial,
                          pitot ? "pitot" : "static",
                          pitot ? "impact" : "static"),
              pitot ? "impact pressure Qc from the test set (kPa)"
                    : "static pressure Ps from the test set (kPa)",
              fmt::format("{} bridge output (ADS1254 code)", pitot ? "pitot" : "static"),
              {},
              {}};
    plot.figure = "ads-raw";
    std::map<double, PlotSeries> by_temp;
    for (const Acquisition& a : points) {
      if (a.n_raw == 0) continue;
      const double bin = std::round(a.raw_temp_c / kTemperatureBinC) * kTemperatureBinC;
      PlotSeries& s = by_temp[bin];
      s.label = fmt::format("{:g} degC", bin);
      s.style = PlotSeries::Style::kPoints;
      s.x.push_back((pitot ? a.qc_ref_pa : a.ps_ref_pa) / 1000.0);
      s.y.push_back(pitot ? a.pt_cnt : a.ps_cnt);
    }
    if (by_temp.empty()) return "";
    for (auto& [bin, s] : by_temp) plot.series.push_back(std::move(s));
    html += RenderSvg(plot);
  }
  return html;
}

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
            "chamber temperature (degC, as the controller reports it)",
            altitude ? "pressure altitude from the test set's Ps, ISA (ft)"
                     : "calibrated airspeed from the test set's Qc (kt)",
            {},
            {}};
  plot.figure = "ads-surface-residual";
  std::array<PlotSeries, 3> classes = {
      PlotSeries{"|residual| <= 1/2 tolerance", {}, {}, PlotSeries::Style::kPoints, "#2ca02c"},
      PlotSeries{
          "1/2 < |residual| / tolerance <= 1", {}, {}, PlotSeries::Style::kPoints, "#ff7f0e"},
      PlotSeries{"|residual| > tolerance", {}, {}, PlotSeries::Style::kPoints, "#d62728"}};
  for (const Acquisition& a : points) {
    if (a.n == 0 || (a.cas_ref_kt >= cas_min_kt) == altitude) continue;
    const double x = altitude ? a.alt_ref_ft : a.cas_ref_kt;
    if (x < tol.input_min() || x > tol.input_max()) continue;
    const double ratio =
        std::abs(altitude ? a.alt_ft - a.alt_ref_ft : a.cas_kt - a.cas_ref_kt) / tol.At(x);
    PlotSeries& s = classes[ratio <= 0.5 ? 0 : ratio <= 1.0 ? 1 : 2];
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
  double alt_ft = 0.0, cas_kt = 0.0;
  if (row.alt_ft && row.cas_kt) {
    alt_ft = *row.alt_ft;
    cas_kt = *row.cas_kt;
    unit_values_ = true;
  } else {
    a.ps_ref_pa += row.ps_ref_pa;
    a.qc_ref_pa += row.qc_ref_pa;
    a.ps_cnt += row.ps_cnt;
    a.pt_cnt += row.pt_cnt;
    a.raw_temp_c += row.chamber_c;
    ++a.n_raw;
    if (constants_ == nullptr) return;
    const fm::AdsRawFrame raw{
        row.ps_cnt, row.pt_cnt, row.ps_temp_cnt, row.pt_temp_cnt, row.oat_cnt};
    const auto v = fm::AdsReference(*constants_->ads, fm::AdsCompensationMode::kSurface, raw);
    alt_ft = v[0];
    cas_kt = v[1];
    reference_values_ = true;
  }
  a.alt_ref_ft += common::IsaPressureAltitudeFt(row.ps_ref_pa);
  a.cas_ref_kt += row.qc_ref_pa > 0.0 ? common::CalibratedAirspeedKt(row.qc_ref_pa) : 0.0;
  a.temp_c += row.chamber_c;
  a.alt_ft += alt_ft;
  a.cas_kt += cas_kt;
  ++a.n;
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
  std::vector<Acquisition> points;  // means
  for (Acquisition a : groups_ | std::views::values) {
    if (a.n > 0) {
      for (double* v : {&a.alt_ref_ft, &a.cas_ref_kt, &a.temp_c, &a.alt_ft, &a.cas_kt}) *v /= a.n;
    }
    if (a.n_raw > 0) {
      for (double* v : {&a.ps_ref_pa, &a.qc_ref_pa, &a.ps_cnt, &a.pt_cnt, &a.raw_temp_c}) {
        *v /= a.n_raw;
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
    const std::string source = unit_values_ && reference_values_
                                   ? "unit output and reference compensator"
                               : unit_values_ ? "the unit's own surface output"
                                              : "reference compensator on raw codes";
    if (reference_values_) {
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
