#include "calib/report/ads_report_sections.h"

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

}  // namespace

AdsReportAccumulator::AdsReportAccumulator(std::string serial,
                                           hil::RecordingMeta meta,
                                           const ConstantsFile* constants)
    : serial_(std::move(serial)), meta_(std::move(meta)), constants_(constants) {}

void AdsReportAccumulator::Add(const hil::AdsRecordRow& row) {
  if (row.unit != serial_ || row.tag == 0 || Rejected(meta_, row.step, row.t_s)) return;
  double alt_ft = 0.0, cas_kt = 0.0;
  if (row.alt_ft && row.cas_kt) {
    alt_ft = *row.alt_ft;
    cas_kt = *row.cas_kt;
    unit_values_ = true;
  } else if (constants_ != nullptr) {
    const fm::AdsRawFrame raw{
        row.ps_cnt, row.pt_cnt, row.ps_temp_cnt, row.pt_temp_cnt, row.oat_cnt};
    const auto v = fm::AdsReference(*constants_->ads, fm::AdsCompensationMode::kSurface, raw);
    alt_ft = v[0];
    cas_kt = v[1];
    reference_values_ = true;
  } else {
    return;
  }
  Acquisition& a =
      groups_[{row.step, row.tag, std::lround(row.ps_ref_pa), std::lround(row.qc_ref_pa)}];
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
  std::vector<Acquisition> points;
  for (Acquisition a : groups_ | std::views::values) {
    for (double* v : {&a.alt_ref_ft, &a.cas_ref_kt, &a.temp_c, &a.alt_ft, &a.cas_kt}) *v /= a.n;
    points.push_back(a);
  }
  std::string map;
  if (points.empty()) {
    map = NotAvailable("ADS error map",
                       constants_ == nullptr ? "raw rows only and no constants.json for " + serial_
                                             : "no tagged acquisition rows for " + serial_);
  } else {
    const std::string source = unit_values_ && reference_values_
                                   ? "unit output and reference compensator"
                               : unit_values_ ? "the unit's own surface output"
                                              : "reference compensator on raw codes";
    map = ErrorPlot(serial_, points, true, source) + ErrorPlot(serial_, points, false, source);
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
