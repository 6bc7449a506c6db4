#include "calib/report/imu_report_sections.h"

#include <array>
#include <cmath>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "calib/report/constants_table.h"
#include "calib/report/html_builder.h"
#include "calib/report/imu_noise_section.h"
#include "calib/report/svg_plot.h"
#include "common/imu_layout.h"
#include "common/units.h"
#include "firmware_model/reference_compensator.h"

namespace adahrs::calib {
namespace {

namespace fm = firmware_model;
using Mode = fm::ImuCompensationMode;

constexpr const char* kAxes[3] = {"x", "y", "z"};
constexpr size_t kMaxPlotPoints = 400;
constexpr double kMpsPerMg = common::kMpsPerMilliG;

std::array<double, 9> Mean(const fm::ImuCalibrationConstants& c,
                           Mode mode,
                           const std::vector<ImuSample>& samples) {
  std::array<double, 9> sum{};
  for (const ImuSample& s : samples) {
    const auto v = fm::ImuReference(c, mode, s.raw);
    for (size_t i = 0; i < 9; ++i) sum[i] += v[i];
  }
  for (double& v : sum) v /= static_cast<double>(samples.size());
  return sum;
}

std::string Unavailable(const std::string& what,
                        const ConstantsFile* constants,
                        const std::string& serial) {
  return NotAvailable(what,
                      constants == nullptr
                          ? "no constants.json for " + serial + " in the fit directory"
                          : "the recording holds no such step");
}

std::string ThermalSection(const ImuUnitData& d, const ConstantsFile* constants) {
  if (d.thermal.empty()) {
    return NotAvailable("Thermal drift",
                        "the recording holds no thermal_profile rows for " + d.serial);
  }
  const size_t stride = std::max<size_t>(1, d.thermal.size() / kMaxPlotPoints);
  const fm::ImuCalibrationConstants none{};
  std::string html;
  for (const bool gyro : {false, true}) {
    Plot drift{
        fmt::format(
            "{} {} raw output over the thermal profile", d.serial, gyro ? "gyro" : "accelerometer"),
        "chamber air temperature (degC, as the controller reports it)",
        gyro ? "U, mean removed (gyro counts)" : "U = T1/T2 - 0.5, mean removed (duty)",
        {},
        {}};
    for (int ch = gyro ? 6 : 0; ch < (gyro ? 9 : 6); ++ch) {
      PlotSeries s{common::kImuChannelNames[ch], {}, {}, PlotSeries::Style::kLine};
      double mean = 0.0;
      for (const ImuSample& x : d.thermal) mean += fm::ImuReference(none, Mode::kRaw, x.raw)[ch];
      mean /= static_cast<double>(d.thermal.size());
      for (size_t i = 0; i < d.thermal.size(); i += stride) {
        s.x.push_back(d.thermal[i].chamber_c);
        s.y.push_back(fm::ImuReference(none, Mode::kRaw, d.thermal[i].raw)[ch] - mean);
      }
      drift.series.push_back(std::move(s));
    }
    html += RenderSvg(drift);
    if (constants == nullptr) continue;
    Plot residual{fmt::format("{} {} thermal fit residual T = U - xi(t), up and down ramps",
                              d.serial,
                              gyro ? "gyro" : "accelerometer"),
                  "chamber air temperature (degC, as the controller reports it)",
                  gyro ? "residual, mean removed (gyro counts)" : "residual, mean removed (duty)",
                  {},
                  {}};
    HtmlTable rms{
        fmt::format("{} thermal fit residual RMS ({})", d.serial, gyro ? "counts" : "duty"),
        {"channel", "up-ramp", "down-ramp", "soak"},
        {}};
    for (int ch = gyro ? 6 : 0; ch < (gyro ? 9 : 6); ++ch) {
      std::vector<double> t(d.thermal.size());
      double mean = 0.0;
      for (size_t i = 0; i < t.size(); ++i) {
        t[i] = fm::ImuReference(*constants->imu, Mode::kThermal, d.thermal[i].raw)[ch];
        mean += t[i];
      }
      mean /= static_cast<double>(t.size());
      std::array<double, 3> sum_sq{}, count{};
      for (const ThermalSegment segment : {ThermalSegment::kUpRamp, ThermalSegment::kDownRamp}) {
        PlotSeries s{fmt::format("{} {}",
                                 common::kImuChannelNames[ch],
                                 segment == ThermalSegment::kUpRamp ? "up" : "down"),
                     {},
                     {},
                     PlotSeries::Style::kPoints};
        for (size_t i = 0; i < t.size(); i += stride) {
          if (d.thermal_segment[i] != segment) continue;
          s.x.push_back(d.thermal[i].chamber_c);
          s.y.push_back(t[i] - mean);
        }
        if (!s.x.empty() && (ch == 0 || ch == 6)) residual.series.push_back(std::move(s));
      }
      for (size_t i = 0; i < t.size(); ++i) {
        const auto k = static_cast<size_t>(d.thermal_segment[i]);
        sum_sq[k] += (t[i] - mean) * (t[i] - mean);
        count[k] += 1.0;
      }
      std::vector<std::string> row = {common::kImuChannelNames[ch]};
      for (size_t k = 0; k < 3; ++k) {
        row.push_back(count[k] > 0 ? FormatNumber(std::sqrt(sum_sq[k] / count[k]), 3) : "no rows");
      }
      rms.rows.push_back(row);
    }
    if (!residual.series.empty()) html += RenderSvg(residual);
    html += RenderTable(rms);
  }
  if (constants == nullptr)
    html += NotAvailable("Thermal fit residuals", "no constants.json for " + d.serial);
  return html;
}

std::string SixPositionSection(const ImuUnitData& d,
                               const ConstantsFile* constants,
                               double g_local_mps2) {
  if (d.accel.empty() || constants == nullptr) {
    return Unavailable("Six-position data", constants, d.serial);
  }
  HtmlTable ca{
      fmt::format("{} mean sensor-calibrated Ca per channel (g; +1 with its axis up)", d.serial),
      {"orientation", "az1", "ax1", "ay1", "az2", "ax2", "ay2"},
      {}};
  HtmlTable residual{fmt::format("{} fully calibrated A - g_local * up (mg), g_local {} m/s^2",
                                 d.serial,
                                 FormatNumber(g_local_mps2, 8)),
                     {"orientation", "x", "y", "z"},
                     {}};
  Plot plot{fmt::format("{} six-position residual of A per axis", d.serial),
            "fixture orientation (code: tens = axis up 1 x, 2 y, 3 z; units = 1 up, 2 down)",
            "A - g_local * up (mg)",
            {},
            {}};
  std::array<PlotSeries, 3> series;
  for (int a = 0; a < 3; ++a)
    series[a] = {std::string("A_") + kAxes[a], {}, {}, PlotSeries::Style::kPoints};
  for (const ImuAcquisition& acq : d.accel) {
    const auto sensor = Mean(*constants->imu, Mode::kSensorCalibrated, acq.samples);
    const auto full = Mean(*constants->imu, Mode::kFullyCalibrated, acq.samples);
    const auto up = UpAxisOf(acq.orientation);
    std::vector<std::string> row = {std::to_string(acq.orientation)};
    for (int ch = 0; ch < 6; ++ch) row.push_back(FormatNumber(sensor[ch], 7));
    ca.rows.push_back(row);
    std::vector<std::string> r = {std::to_string(acq.orientation)};
    for (int a = 0; a < 3; ++a) {
      const double e_mg = (full[a] - g_local_mps2 * up[a]) / kMpsPerMg;
      r.push_back(FormatNumber(e_mg, 3));
      series[a].x.push_back(acq.orientation);
      series[a].y.push_back(e_mg);
    }
    residual.rows.push_back(r);
  }
  for (auto& s : series) plot.series.push_back(std::move(s));
  return RenderTable(ca) + RenderTable(residual) + RenderSvg(plot);
}

std::string GyroSection(const ImuUnitData& d, const ConstantsFile* constants) {
  if (d.gyro.empty() || constants == nullptr) {
    return Unavailable("Gyro nonlinearity", constants, d.serial);
  }
  Plot plot{fmt::format("{} gyro scale-factor fit residual (Eq. 23)", d.serial),
            "table rate about the up axis (deg/s, as the table reports it)",
            "Cg - table rate (deg/s)",
            {},
            {}};
  std::map<std::string, PlotSeries> series;
  HtmlTable table{fmt::format("{} mean sensor-calibrated rate residual (deg/s)", d.serial),
                  {"orientation", "table rate (deg/s)", "channel", "residual (deg/s)"},
                  {}};
  for (const ImuAcquisition& acq : d.gyro) {
    const auto up = UpAxisOf(acq.orientation);
    int axis = 0;
    for (int a = 0; a < 3; ++a) {
      if (std::abs(up[a]) > 0.5) axis = a;
    }
    const auto mean = Mean(*constants->imu, Mode::kSensorCalibrated, acq.samples);
    const double residual = mean[6 + axis] - acq.rate_dps * up[axis];
    const std::string channel = common::kImuChannelNames[6 + axis];
    auto& s = series[channel];
    s.label = channel;
    s.x.push_back(acq.rate_dps * up[axis]);
    s.y.push_back(residual);
    table.rows.push_back({std::to_string(acq.orientation),
                          FormatNumber(acq.rate_dps, 6),
                          channel,
                          FormatNumber(residual, 3)});
  }
  for (auto& [name, s] : series) plot.series.push_back(std::move(s));
  return RenderSvg(plot) + RenderTable(table);
}

std::string MatrixTable(const std::string& caption,
                        const std::array<std::array<double, 3>, 3>& m,
                        const nlohmann::json& se) {
  HtmlTable table{caption, {"row", "col 1", "col 2", "col 3"}, {}};
  for (int r = 0; r < 3; ++r) {
    std::vector<std::string> row = {std::to_string(r + 1)};
    for (int c = 0; c < 3; ++c) {
      const nlohmann::json& e = se.is_array() ? se[r][c] : nlohmann::json();
      row.push_back(FormatNumber(m[r][c], 8) + " ± " +
                    (e.is_number() ? FormatNumber(e.get<double>(), 2) : "n/a"));
    }
    table.rows.push_back(row);
  }
  return RenderTable(table);
}

std::string CrossAxisSection(const ImuUnitData& d,
                             const ConstantsFile* constants,
                             double g_local_mps2) {
  if (constants == nullptr) return Unavailable("Cross-axis", constants, d.serial);
  const nlohmann::json& se = constants->standard_errors;
  std::string html =
      MatrixTable(d.serial + " CA (m/s^2 per g) ± 1-sigma standard error",
                  constants->imu->ca_mps2_per_g,
                  se.is_object() ? se.value("ca_mps2_per_g", nlohmann::json()) : nlohmann::json()) +
      MatrixTable(d.serial + " CG (deg/s per deg/s) ± 1-sigma standard error",
                  constants->imu->cg,
                  se.is_object() ? se.value("cg", nlohmann::json()) : nlohmann::json());
  if (d.cross_axis.empty()) {
    return html + NotAvailable("Cross-axis residuals", "the recording holds no cross_axis step");
  }
  HtmlTable table{d.serial + " fully calibrated residuals in the cross-axis acquisitions",
                  {"orientation",
                   "table rate (deg/s)",
                   "A - g_local*up x, y, z (mg)",
                   "G - rate*up x, y, z (deg/s)"},
                  {}};
  for (const ImuAcquisition& acq : d.cross_axis) {
    const auto full = Mean(*constants->imu, Mode::kFullyCalibrated, acq.samples);
    const auto up = UpAxisOf(acq.orientation);
    std::vector<std::string> a, g;
    for (int i = 0; i < 3; ++i) {
      a.push_back(FormatNumber((full[i] - g_local_mps2 * up[i]) / kMpsPerMg, 3));
      g.push_back(FormatNumber(full[3 + i] - acq.rate_dps * up[i], 3));
    }
    table.rows.push_back({std::to_string(acq.orientation),
                          FormatNumber(acq.rate_dps, 6),
                          fmt::format("{}", fmt::join(a, ", ")),
                          fmt::format("{}", fmt::join(g, ", "))});
  }
  return html + RenderTable(table);
}

}  // namespace

std::string ImuReportSections(const ImuUnitData& data,
                              const ConstantsFile* constants,
                              double local_gravity_mps2) {
  const std::string id = data.serial;
  std::string html;
  html +=
      Section(id + "-constants",
              3,
              data.serial + " constants",
              constants != nullptr
                  ? ConstantsSection(*constants)
                  : NotAvailable("Constants",
                                 "no constants.json for " + data.serial + " in the fit directory"));
  html += Section(id + "-thermal",
                  3,
                  data.serial + " thermal drift and fit residuals",
                  ThermalSection(data, constants));
  html += Section(id + "-six-position",
                  3,
                  data.serial + " six-position data",
                  SixPositionSection(data, constants, local_gravity_mps2));
  html += Section(
      id + "-gyro", 3, data.serial + " gyro nonlinearity fit", GyroSection(data, constants));
  html += Section(id + "-cross-axis",
                  3,
                  data.serial + " cross-axis",
                  CrossAxisSection(data, constants, local_gravity_mps2));
  html += Section(id + "-noise",
                  3,
                  data.serial + " noise (Allan deviation at rest)",
                  ImuNoiseSection(data, constants));
  return html;
}

}  // namespace adahrs::calib
