#include "calib/report/time_series.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "calib/report/svg_plot.h"
#include "common/imu_layout.h"

namespace adahrs::calib {
namespace {

constexpr const char* kInstruments = "Instruments";

}  // namespace

void DecimatedSeries::Add(double t_s, double value) {
  if (!std::isfinite(t_s) || !std::isfinite(value)) return;
  if (bins_.empty()) t0_s_ = t_s;
  if (t_s < t0_s_) return;  // before the first row: not drawn
  while (std::floor((t_s - t0_s_) / width_s_) >= static_cast<double>(kTimeSeriesBins)) Halve();
  const double start_s = t0_s_ + std::floor((t_s - t0_s_) / width_s_) * width_s_;
  if (bins_.empty() || bins_.back().t_s < start_s) {
    bins_.push_back({start_s, value, value});
    return;
  }
  Bin& b = bins_.back();
  b.lo = std::min(b.lo, value);
  b.hi = std::max(b.hi, value);
}

void DecimatedSeries::Halve() {
  width_s_ *= 2.0;
  std::vector<Bin> merged;
  for (const Bin& b : bins_) {
    const double start_s = t0_s_ + std::floor((b.t_s - t0_s_) / width_s_) * width_s_;
    if (merged.empty() || merged.back().t_s < start_s) {
      merged.push_back({start_s, b.lo, b.hi});
    } else {
      merged.back().lo = std::min(merged.back().lo, b.lo);
      merged.back().hi = std::max(merged.back().hi, b.hi);
    }
  }
  bins_ = std::move(merged);
}

void DecimatedSeries::Envelope(std::vector<double>& t_s, std::vector<double>& value) const {
  for (const Bin& b : bins_) {
    const double mid_s = b.t_s + 0.5 * width_s_;
    t_s.insert(t_s.end(), {mid_s, mid_s});
    value.insert(value.end(), {b.lo, b.hi});
  }
}

TimeSeriesAccumulator::Figure& TimeSeriesAccumulator::FigureOf(const std::string& title,
                                                               const std::string& y_label) {
  auto [it, added] = figures_.try_emplace(title);
  if (added) {
    order_.push_back(title);
    it->second.y_label = y_label;
  }
  return it->second;
}

void TimeSeriesAccumulator::Step(double t_s, int step) {
  if (step != last_step_) step_starts_s_.push_back(t_s);
  last_step_ = step;
}

void TimeSeriesAccumulator::Add(const hil::ImuRecordRow& r) {
  if (instrument_unit_.empty()) instrument_unit_ = r.unit;
  if (r.unit == instrument_unit_) {
    Step(r.t_s, r.step);
    FigureOf(kInstruments, "reading (degC, deg/s)")
        .series["chamber (degC)"]
        .Add(r.t_s, r.chamber_c);
    FigureOf(kInstruments, "").series["rate table (deg/s)"].Add(r.t_s, r.table_rate_dps);
  }
  if (r.comp && r.mode == 3) {  // fully calibrated: A (m/s^2) 0..2, G (deg/s) 3..5
    Figure& a = FigureOf(r.unit + ": accelerations (mode 3)", "acceleration (m/s^2)");
    Figure& g = FigureOf(r.unit + ": body rates (mode 3)", "rate (deg/s)");
    for (int axis = 0; axis < 3; ++axis) {
      a.series[fmt::format("A{}", "xyz"[axis])].Add(r.t_s, (*r.comp)[axis]);
      g.series[fmt::format("G{}", "xyz"[axis])].Add(r.t_s, (*r.comp)[3 + axis]);
    }
    return;
  }
  if (r.comp && r.mode == 2) {  // sensor calibrated: g per channel 0..5, deg/s 6..8
    Figure& a = FigureOf(r.unit + ": accelerometer channels (mode 2)", "acceleration (g)");
    Figure& g = FigureOf(r.unit + ": gyro channels (mode 2)", "rate (deg/s)");
    for (int ch = 0; ch < 6; ++ch)
      a.series[common::kAccelChannelNames[ch]].Add(r.t_s, (*r.comp)[ch]);
    for (int axis = 0; axis < 3; ++axis) {
      g.series[common::kGyroChannelNames[axis]].Add(r.t_s, (*r.comp)[6 + axis]);
    }
    return;
  }
  // Raw rows, and thermally compensated ones (mode 1: the same slots, drift removed) as raw.
  Figure& g = FigureOf(r.unit + ": gyro counts (raw)", "gyro output (counts)");
  for (int axis = 0; axis < 3; ++axis) {
    g.series[common::kGyroChannelNames[axis]].Add(r.t_s, r.gyro_cnt[axis]);
  }
  Figure& a = FigureOf(r.unit + ": accelerometer duty (raw)", "duty T1/T2 - 0.5 (dimensionless)");
  for (int ch = 0; ch < 6; ++ch) {
    const double t2 = r.accel_ticks[2 * ch + 1];
    if (t2 > 0.0)
      a.series[common::kAccelChannelNames[ch]].Add(r.t_s, r.accel_ticks[2 * ch] / t2 - 0.5);
  }
}

void TimeSeriesAccumulator::Add(const hil::AdsRecordRow& r) {
  if (instrument_unit_.empty()) instrument_unit_ = r.unit;
  if (r.unit == instrument_unit_) {
    Step(r.t_s, r.step);
    Figure& f = FigureOf(kInstruments, "reading (degC, kPa)");
    f.series["chamber (degC)"].Add(r.t_s, r.chamber_c);
    f.series["static pressure (kPa)"].Add(r.t_s, r.ps_ref_pa / 1000.0);
    f.series["impact pressure (kPa)"].Add(r.t_s, r.qc_ref_pa / 1000.0);
  }
  if (r.alt_ft && r.cas_kt) {
    FigureOf(r.unit + ": altitude (surface mode)", "altitude (ft)")
        .series["altitude"]
        .Add(r.t_s, *r.alt_ft);
    FigureOf(r.unit + ": airspeed (surface mode)", "airspeed (kt)")
        .series["airspeed"]
        .Add(r.t_s, *r.cas_kt);
    return;
  }
  Figure& f = FigureOf(r.unit + ": bridge codes (raw)", "bridge output (ADS1254 code)");
  f.series["static"].Add(r.t_s, r.ps_cnt);
  f.series["pitot"].Add(r.t_s, r.pt_cnt);
}

std::string TimeSeriesAccumulator::Figures() const {
  std::string html;
  for (const std::string& title : order_) {
    const Figure& f = figures_.at(title);
    Plot plot{title, "time on the run's time base (s)", f.y_label, {}, {}};
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& [label, s] : f.series) {
      PlotSeries series{label, {}, {}};
      s.Envelope(series.x, series.y);
      for (double v : series.y) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
      plot.series.push_back(std::move(series));
    }
    if (title == kInstruments && std::isfinite(lo) && step_starts_s_.size() > 1) {
      // One series of vertical marks, broken between steps by non-finite points.
      PlotSeries marks{"step starts", {}, {}};
      for (double t_s : step_starts_s_) {
        marks.x.insert(marks.x.end(), {t_s, t_s, std::nan("")});
        marks.y.insert(marks.y.end(), {lo, hi, std::nan("")});
      }
      plot.series.push_back(std::move(marks));
    }
    html += RenderSvg(plot);
  }
  return html;
}

}  // namespace adahrs::calib
