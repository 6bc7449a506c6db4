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
constexpr size_t kMaxSmallPlotPoints = 100;  // per series of a one-channel figure
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

// Figures of one channel are small, three to a row of the page.
constexpr int kSmallWidthPx = 400;
constexpr int kSmallHeightPx = 250;
constexpr int kFitCurvePoints = 80;
// Acquisitions within this of a group's first temperature belong to its series (the soaks of one
// calibration temperature, held in a +-0.5 degC band).
constexpr double kTemperatureGroupC = 3.0;
// A gyro acquisition at the table's 0 deg/s.
constexpr double kAtRestDps = 0.5;

std::string Units(bool gyro) { return gyro ? "gyro counts" : "duty"; }

// The driving temperature count of channel `ch` in `raw`.
double TempCount(const fm::ThermalFit& f, const fm::ImuRawFrame& raw) {
  return raw.temp_cnt[static_cast<size_t>(f.temp_sensor)];
}

// Raw output against chamber temperature, every channel of a group (no fit to compare with).
std::string DriftOverview(const ImuUnitData& d, bool gyro, size_t stride) {
  const fm::ImuCalibrationConstants none{};
  Plot drift{
      fmt::format(
          "{} {} raw output over the thermal profile", d.serial, gyro ? "gyro" : "accelerometer"),
      "chamber air temperature (degC, as the controller reports it)",
      gyro ? "U, mean removed (gyro counts)" : "U = T1/T2 - 0.5, mean removed (duty)",
      {},
      {}};
  drift.figure = "thermal-raw";
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
  return RenderSvg(drift);
}

// Channel `ch`'s raw output against its temperature sensor's count with the fitted xi(t) over
// the profile's count range (both with the mean over the profile's rows removed), and its
// residual T = U - xi(t) against chamber temperature, up- and down-ramps apart.
std::string ChannelThermalFigures(const ImuUnitData& d,
                                  const fm::ImuCalibrationConstants& c,
                                  int ch,
                                  size_t stride) {
  const fm::ThermalFit& fit = c.thermal[static_cast<size_t>(ch)];
  const bool gyro = ch >= 6;
  const std::string name = common::kImuChannelNames[static_cast<size_t>(ch)];
  const fm::ImuCalibrationConstants none{};
  std::vector<double> u(d.thermal.size()), t(d.thermal.size());
  double u_mean = 0.0, xi_mean = 0.0, t_lo = 1e300, t_hi = -1e300;
  for (size_t i = 0; i < d.thermal.size(); ++i) {
    u[i] = fm::ImuReference(none, Mode::kRaw, d.thermal[i].raw)[static_cast<size_t>(ch)];
    t[i] = TempCount(fit, d.thermal[i].raw);
    u_mean += u[i];
    xi_mean += fm::ThermalDrift(fit, t[i]);
    t_lo = std::min(t_lo, t[i]);
    t_hi = std::max(t_hi, t[i]);
  }
  u_mean /= static_cast<double>(u.size());
  xi_mean /= static_cast<double>(u.size());

  Plot raw{fmt::format("{} {}: raw output and fitted xi(t)", d.serial, name),
           fmt::format("temperature sensor {} (TEMP counts)",
                       common::kGyroChannelNames[static_cast<size_t>(fit.temp_sensor)]),
           fmt::format("U - mean ({})", Units(gyro)),
           {},
           {}};
  raw.figure = "thermal-fit";
  raw.width_px = kSmallWidthPx;
  raw.height_px = kSmallHeightPx;
  PlotSeries points{"recorded U", {}, {}, PlotSeries::Style::kPoints};
  for (size_t i = 0; i < u.size(); i += stride) {
    points.x.push_back(t[i]);
    points.y.push_back(u[i] - u_mean);
  }
  PlotSeries curve{"fitted xi(t)", {}, {}, PlotSeries::Style::kLine};
  for (int k = 0; k <= kFitCurvePoints; ++k) {
    const double tc = t_lo + (t_hi - t_lo) * k / kFitCurvePoints;
    curve.x.push_back(tc);
    curve.y.push_back(fm::ThermalDrift(fit, tc) - xi_mean);
  }
  raw.series = {std::move(points), std::move(curve)};

  Plot residual{fmt::format("{} {}: residual after the thermal fit", d.serial, name),
                "chamber temperature (degC)",
                fmt::format("T = U - xi(t), mean removed ({})", Units(gyro)),
                {},
                {}};
  residual.figure = "thermal-residual";
  residual.width_px = kSmallWidthPx;
  residual.height_px = kSmallHeightPx;
  double r_mean = 0.0;
  for (size_t i = 0; i < u.size(); ++i) r_mean += u[i] - fm::ThermalDrift(fit, t[i]);
  r_mean /= static_cast<double>(u.size());
  for (const ThermalSegment segment : {ThermalSegment::kUpRamp, ThermalSegment::kDownRamp}) {
    PlotSeries s{segment == ThermalSegment::kUpRamp ? "up-ramp" : "down-ramp",
                 {},
                 {},
                 PlotSeries::Style::kPoints};
    for (size_t i = 0; i < u.size(); i += stride) {
      if (d.thermal_segment[i] != segment) continue;
      s.x.push_back(d.thermal[i].chamber_c);
      s.y.push_back(u[i] - fm::ThermalDrift(fit, t[i]) - r_mean);
    }
    if (!s.x.empty()) residual.series.push_back(std::move(s));
  }
  return RenderSvg(raw) + (residual.series.empty() ? "" : RenderSvg(residual));
}

std::string ThermalSection(const ImuUnitData& d, const ConstantsFile* constants) {
  if (d.thermal.empty()) {
    return NotAvailable("Thermal drift",
                        "the recording holds no thermal_profile rows for " + d.serial);
  }
  std::string html;
  if (constants == nullptr) {
    const size_t stride = std::max<size_t>(1, d.thermal.size() / kMaxPlotPoints);
    html = DriftOverview(d, false, stride) + DriftOverview(d, true, stride);
    return html + NotAvailable("Thermal fit and residuals", "no constants.json for " + d.serial);
  }
  const size_t small_stride = std::max<size_t>(1, d.thermal.size() / kMaxSmallPlotPoints);
  for (const bool gyro : {false, true}) {
    html += "<div class=\"figures\">\n";
    for (int ch = gyro ? 6 : 0; ch < (gyro ? 9 : 6); ++ch) {
      html += ChannelThermalFigures(d, *constants->imu, ch, small_stride);
    }
    html += "</div>\n";
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
    html += RenderTable(rms);
  }
  return html;
}

double MeanChamberC(const ImuAcquisition& acq) {
  double sum = 0.0;
  for (const ImuSample& s : acq.samples) sum += s.chamber_c;
  return acq.samples.empty() ? std::nan("") : sum / static_cast<double>(acq.samples.size());
}

std::string SixPositionSection(const ImuUnitData& d,
                               const ConstantsFile* constants,
                               double g_local_mps2) {
  if (d.accel.empty() || constants == nullptr) {
    return Unavailable("Six-position data", constants, d.serial);
  }
  HtmlTable ca{
      fmt::format("{} mean sensor-calibrated Ca per channel (g; +1 with its axis up)", d.serial),
      {"chamber (degC)", "orientation", "az1", "ax1", "ay1", "az2", "ax2", "ay2"},
      {}};
  HtmlTable residual{fmt::format("{} fully calibrated A - g_local * up (mg), g_local {} m/s^2",
                                 d.serial,
                                 FormatNumber(g_local_mps2, 8)),
                     {"chamber (degC)", "orientation", "x", "y", "z"},
                     {}};
  Plot plot{fmt::format("{} six-position residual of A per axis", d.serial),
            "fixture orientation (code: tens = axis up 1 x, 2 y, 3 z; units = 1 up, 2 down)",
            "A - g_local * up (mg)",
            {},
            {}};
  plot.figure = "six-position-residual";
  std::array<PlotSeries, 3> series;
  for (int a = 0; a < 3; ++a)
    series[a] = {std::string("A_") + kAxes[a], {}, {}, PlotSeries::Style::kPoints};
  for (const ImuAcquisition& acq : d.accel) {
    const auto sensor = Mean(*constants->imu, Mode::kSensorCalibrated, acq.samples);
    const auto full = Mean(*constants->imu, Mode::kFullyCalibrated, acq.samples);
    const auto up = UpAxisOf(acq.orientation);
    const std::string chamber = FormatNumber(MeanChamberC(acq), 4);
    std::vector<std::string> row = {chamber, std::to_string(acq.orientation)};
    for (int ch = 0; ch < 6; ++ch) row.push_back(FormatNumber(sensor[ch], 7));
    ca.rows.push_back(row);
    std::vector<std::string> r = {chamber, std::to_string(acq.orientation)};
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

// The body axis a gyro acquisition turns about (its orientation's up axis) and the sign.
int UpAxisIndex(const std::array<double, 3>& up) {
  int axis = 0;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(up[a]) > 0.5) axis = a;
  }
  return axis;
}

// The mean of the gyro cubic's input d = (T - null) F(t) over an acquisition (Eq. 23 normalised
// means; F = 1 without format-3 terms).
double MeanCubicInput(const fm::ImuCalibrationConstants& c,
                      int axis,
                      const std::vector<ImuSample>& samples) {
  const int ch = 6 + axis;
  double sum = 0.0;
  for (const ImuSample& s : samples) {
    const double t = fm::ImuReference(c, Mode::kThermal, s.raw)[static_cast<size_t>(ch)];
    sum +=
        (t - c.gyro[static_cast<size_t>(axis)].null_cnt) * fm::ScaleTemperatureFactor(c, ch, s.raw);
  }
  return sum / static_cast<double>(samples.size());
}

double MeanRaw(int ch, const std::vector<ImuSample>& samples) {
  const fm::ImuCalibrationConstants none{};
  double sum = 0.0;
  for (const ImuSample& s : samples) sum += fm::ImuReference(none, Mode::kRaw, s.raw)[ch];
  return sum / static_cast<double>(samples.size());
}

// Fig. 23 of the reference: per gyro, the normalised means against the table rate, one series
// per chamber temperature, and the fitted cubic.
std::string GyroScaleCurves(const ImuUnitData& d, const fm::ImuCalibrationConstants& c) {
  std::string html = "<div class=\"figures\">\n";
  for (int axis = 0; axis < 3; ++axis) {
    Plot plot{fmt::format("{} {}: scale-factor curve (Eq. 23)",
                          d.serial,
                          common::kGyroChannelNames[static_cast<size_t>(axis)]),
              "table rate about the gyro's axis (deg/s)",
              "normalised mean (T - null) F(t) (gyro counts)",
              {},
              {}};
    plot.figure = "gyro-scale";
    plot.width_px = kSmallWidthPx;
    plot.height_px = kSmallHeightPx + 40;
    std::vector<PlotSeries> by_temp;  // one per temperature the acquisitions cluster at
    std::vector<double> group_c;      // each series' first acquisition's temperature
    double lo = 1e300, hi = -1e300;
    for (const ImuAcquisition& acq : d.gyro) {
      const auto up = UpAxisOf(acq.orientation);
      if (UpAxisIndex(up) != axis || acq.samples.empty()) continue;
      const double temp_c = MeanChamberC(acq);
      size_t g = 0;
      while (g < group_c.size() && std::abs(group_c[g] - temp_c) > kTemperatureGroupC) ++g;
      if (g == group_c.size()) {
        group_c.push_back(temp_c);
        by_temp.push_back({fmt::format("means at {:.0f} degC", temp_c + 0.0),
                           {},
                           {},
                           PlotSeries::Style::kPoints});
      }
      PlotSeries& s = by_temp[g];
      const double input = MeanCubicInput(c, axis, acq.samples);
      s.x.push_back(acq.rate_dps * up[static_cast<size_t>(axis)]);
      s.y.push_back(input);
      lo = std::min(lo, input);
      hi = std::max(hi, input);
    }
    if (by_temp.empty()) continue;
    for (PlotSeries& s : by_temp) plot.series.push_back(std::move(s));
    PlotSeries cubic{"fitted cubic l0 + l1 d + l2 d^2 + l3 d^3", {}, {}, PlotSeries::Style::kLine};
    for (int k = 0; k <= kFitCurvePoints; ++k) {
      const double v = lo + (hi - lo) * k / kFitCurvePoints;
      cubic.x.push_back(fm::GyroCubic(c, axis, v));
      cubic.y.push_back(v);
    }
    plot.series.push_back(std::move(cubic));
    html += RenderSvg(plot);
  }
  return html + "</div>\n";
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
  plot.figure = "gyro-residual";
  std::map<std::string, PlotSeries> series;
  HtmlTable table{
      fmt::format("{} gyro means per rate: raw, normalised by the step's 0 deg/s mean, and the "
                  "sensor-calibrated residual",
                  d.serial),
      {"chamber (degC)",
       "orientation",
       "table rate (deg/s)",
       "channel",
       "mean raw (counts)",
       "normalised (counts)",
       "residual (deg/s)"},
      {}};
  // The mean raw output at the table's 0 deg/s of each step and channel (Table 17's reference).
  std::map<std::pair<int, int>, double> at_rest;
  for (const ImuAcquisition& acq : d.gyro) {
    const int axis = UpAxisIndex(UpAxisOf(acq.orientation));
    if (std::abs(acq.rate_dps) < kAtRestDps && !acq.samples.empty()) {
      at_rest[{acq.step, axis}] = MeanRaw(6 + axis, acq.samples);
    }
  }
  for (const ImuAcquisition& acq : d.gyro) {
    const auto up = UpAxisOf(acq.orientation);
    const int axis = UpAxisIndex(up);
    const auto mean = Mean(*constants->imu, Mode::kSensorCalibrated, acq.samples);
    const double residual = mean[6 + axis] - acq.rate_dps * up[axis];
    const std::string channel = common::kImuChannelNames[6 + axis];
    auto& s = series[channel];
    s.label = channel;
    s.x.push_back(acq.rate_dps * up[axis]);
    s.y.push_back(residual);
    const double raw = MeanRaw(6 + axis, acq.samples);
    const auto rest = at_rest.find({acq.step, axis});
    table.rows.push_back(
        {FormatNumber(MeanChamberC(acq), 4),
         std::to_string(acq.orientation),
         FormatNumber(acq.rate_dps, 6),
         channel,
         FormatNumber(raw, 8),
         rest == at_rest.end() ? "no 0 deg/s mean" : FormatNumber(raw - rest->second, 8),
         FormatNumber(residual, 3)});
  }
  for (auto& [name, s] : series) plot.series.push_back(std::move(s));
  return GyroScaleCurves(d, *constants->imu) + RenderSvg(plot) + RenderTable(table);
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
