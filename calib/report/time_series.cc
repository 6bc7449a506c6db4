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

namespace {

// One figure of a layout: its title (after "<unit>: "; the instruments' figure has none), y axis
// and series.
struct FigureLayout {
  const char* title;
  const char* y_label;
  std::vector<std::string> labels;
};

std::vector<FigureLayout> FiguresOf(TimeSeriesAccumulator::Layout layout) {
  using L = TimeSeriesAccumulator::Layout;
  const std::vector<std::string> accel(std::begin(common::kAccelChannelNames),
                                       std::end(common::kAccelChannelNames));
  const std::vector<std::string> gyro(std::begin(common::kGyroChannelNames),
                                      std::end(common::kGyroChannelNames));
  switch (layout) {
    case L::kImuInstruments:
      return {{kInstruments, "reading (degC, deg/s)", {"chamber (degC)", "rate table (deg/s)"}}};
    case L::kAdsInstruments:
      return {{kInstruments,
               "reading (degC, kPa)",
               {"chamber (degC)", "static pressure (kPa)", "impact pressure (kPa)"}}};
    case L::kImuMode3:  // fully calibrated: A (m/s^2) 0..2, G (deg/s) 3..5
      return {{"accelerations (mode 3)", "acceleration (m/s^2)", {"Ax", "Ay", "Az"}},
              {"body rates (mode 3)", "rate (deg/s)", {"Gx", "Gy", "Gz"}}};
    case L::kImuMode2:  // sensor calibrated: g per channel 0..5, deg/s 6..8
      return {{"accelerometer channels (mode 2)", "acceleration (g)", accel},
              {"gyro channels (mode 2)", "rate (deg/s)", gyro}};
    case L::kImuRaw:
      return {{"gyro counts (raw)", "gyro output (counts)", gyro},
              {"accelerometer duty (raw)", "duty T1/T2 - 0.5 (dimensionless)", accel}};
    case L::kAdsSurface:
      return {{"altitude (surface mode)", "altitude (ft)", {"altitude"}},
              {"airspeed (surface mode)", "airspeed (kt)", {"airspeed"}}};
    case L::kAdsRaw:
      return {{"bridge codes (raw)", "bridge output (ADS1254 code)", {"static", "pitot"}}};
  }
  return {};
}

bool IsInstruments(TimeSeriesAccumulator::Layout layout) {
  return layout == TimeSeriesAccumulator::Layout::kImuInstruments ||
         layout == TimeSeriesAccumulator::Layout::kAdsInstruments;
}

}  // namespace

TimeSeriesAccumulator::Feed& TimeSeriesAccumulator::FeedOf(const std::string& unit, Layout layout) {
  for (Feed& f : feeds_) {
    if (f.layout == layout && f.unit == unit) return f;
  }
  Feed feed{unit, layout, {}};
  for (const FigureLayout& fl : FiguresOf(layout)) {
    const std::string title =
        IsInstruments(layout) ? std::string(fl.title) : unit + ": " + fl.title;
    Figure& figure = figures_.emplace_back();
    figure.title = title;
    figure.y_label = fl.y_label;
    figure.labels = fl.labels;
    figure.series.resize(fl.labels.size());
    for (DecimatedSeries& s : figure.series) feed.series.push_back(&s);
  }
  feeds_.push_back(std::move(feed));
  return feeds_.back();
}

void TimeSeriesAccumulator::Step(double t_s, int step) {
  if (step != last_step_) step_starts_s_.push_back(t_s);
  last_step_ = step;
}

void TimeSeriesAccumulator::Add(const hil::ImuRecordRow& r) {
  if (instrument_unit_.empty()) instrument_unit_ = r.unit;
  if (r.unit == instrument_unit_) {
    Step(r.t_s, r.step);
    const Feed& f = FeedOf(r.unit, Layout::kImuInstruments);
    f.series[0]->Add(r.t_s, r.chamber_c);
    f.series[1]->Add(r.t_s, r.table_rate_dps);
  }
  if (r.comp && r.mode == 3) {
    const Feed& f = FeedOf(r.unit, Layout::kImuMode3);
    for (size_t i = 0; i < 6; ++i) f.series[i]->Add(r.t_s, (*r.comp)[i]);
    return;
  }
  if (r.comp && r.mode == 2) {
    const Feed& f = FeedOf(r.unit, Layout::kImuMode2);
    for (size_t i = 0; i < 9; ++i) f.series[i]->Add(r.t_s, (*r.comp)[i]);
    return;
  }
  // Raw rows, and thermally compensated ones (mode 1: the same slots, drift removed) as raw.
  const Feed& f = FeedOf(r.unit, Layout::kImuRaw);
  for (size_t axis = 0; axis < 3; ++axis) f.series[axis]->Add(r.t_s, r.gyro_cnt[axis]);
  for (size_t ch = 0; ch < 6; ++ch) {
    const double t2 = r.accel_ticks[2 * ch + 1];
    if (t2 > 0.0) f.series[3 + ch]->Add(r.t_s, r.accel_ticks[2 * ch] / t2 - 0.5);
  }
}

void TimeSeriesAccumulator::Add(const hil::AdsRecordRow& r) {
  if (instrument_unit_.empty()) instrument_unit_ = r.unit;
  if (r.unit == instrument_unit_) {
    Step(r.t_s, r.step);
    const Feed& f = FeedOf(r.unit, Layout::kAdsInstruments);
    f.series[0]->Add(r.t_s, r.chamber_c);
    f.series[1]->Add(r.t_s, r.ps_ref_pa / 1000.0);
    f.series[2]->Add(r.t_s, r.qc_ref_pa / 1000.0);
  }
  if (r.alt_ft && r.cas_kt) {
    const Feed& f = FeedOf(r.unit, Layout::kAdsSurface);
    f.series[0]->Add(r.t_s, *r.alt_ft);
    f.series[1]->Add(r.t_s, *r.cas_kt);
    return;
  }
  const Feed& f = FeedOf(r.unit, Layout::kAdsRaw);
  f.series[0]->Add(r.t_s, r.ps_cnt);
  f.series[1]->Add(r.t_s, r.pt_cnt);
}

std::string TimeSeriesAccumulator::Figures() const {
  std::string html;
  for (const Figure& f : figures_) {
    Plot plot{f.title, "time on the run's time base (s)", f.y_label, {}, {}};
    plot.figure = "time-series";
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (size_t i = 0; i < f.series.size(); ++i) {
      if (f.series[i].empty()) continue;
      PlotSeries series{f.labels[i], {}, {}};
      f.series[i].Envelope(series.x, series.y);
      for (double v : series.y) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
      plot.series.push_back(std::move(series));
    }
    if (plot.series.empty()) continue;
    if (f.title == kInstruments && std::isfinite(lo) && step_starts_s_.size() > 1) {
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
