#include "diagnosis/diagnosis_cells.h"

#include "common/imu_layout.h"
#include "diagnosis/last_change_sense.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

namespace adahrs::diagnosis {
namespace {

constexpr double kMaxRowGap_s = 0.05;     // a longer gap (lost packets) closes a cell
constexpr double kMaxTrendGap_s = 120.0;  // the rate window never bridges a longer gap
constexpr double kMinFittedSpan_c = 5.0;  // soaks this far apart fit the thermometer's slope

double Output(const calib::ImuSample& s, int channel) {
  if (channel < 6) {
    return static_cast<double>(s.raw.t1_cnt[channel]) / static_cast<double>(s.raw.t2_cnt[channel]) -
           0.5;
  }
  return static_cast<double>(s.raw.gyro_cnt[channel - 6]);
}

Eigen::Vector3d Up(int orientation) {
  if (orientation == 0) return Eigen::Vector3d::Zero();
  const std::array<double, 3> up = calib::UpAxisOf(orientation);
  return {up[0], up[1], up[2]};
}

// Accumulates consecutive rows of one segment into cells.
class CellCutter {
 public:
  /// `frame_period_s` > 0: the spectra take each row's time from the packet counter (frames since
  /// the segment's first row), not from its arrival time, which comes in bursts on a real line.
  CellCutter(DiagnosisData* data, double cell_s, double frame_period_s)
      : data_(data), cell_s_(cell_s), frame_period_s_(frame_period_s) {}

  void Segment(DiagnosisSegment segment,
               const std::vector<const calib::ImuSample*>& rows,
               const Eigen::Vector3d& f_B_g,
               const Eigen::Vector3d& w_B_dps) {
    if (rows.empty()) return;
    const int index = static_cast<int>(data_->segments.size());
    segment.t_first_s = rows.front()->t_s;
    segment.t_last_s = rows.back()->t_s;
    segment.rows = static_cast<int>(rows.size());
    double chamber = 0.0;
    size_t begin = 0;
    for (size_t i = 0; i < rows.size(); ++i) {
      chamber += rows[i]->chamber_c;
      const bool last = i + 1 == rows.size();
      if (last || rows[i + 1]->t_s - rows[begin]->t_s >= cell_s_ ||
          rows[i + 1]->t_s - rows[i]->t_s > kMaxRowGap_s) {
        AddCell(index, rows, begin, i + 1, f_B_g, w_B_dps);
        begin = i + 1;
      }
    }
    segment.chamber_mean_c = chamber / static_cast<double>(rows.size());
    CountSequenceGaps(rows);
    std::vector<double> t(rows.size());
    for (size_t i = 0; i < rows.size(); ++i) {
      t[i] =
          frame_period_s_ > 0.0 && i > 0
              ? t[i - 1] + static_cast<uint8_t>(rows[i]->seq - rows[i - 1]->seq) * frame_period_s_
              : rows[i]->t_s;
    }
    for (RowSpectra* spectra : {&data_->spectra, &data_->slow_spectra}) {
      spectra->AddSegment(
          index,
          rows.size(),
          [&](size_t i) { return t[i]; },
          [&](size_t i, int ch) { return Output(*rows[i], ch); });
    }
    MeasureRippleOfSegment(index, rows, t, w_B_dps);
    data_->rows += segment.rows;
    data_->segments.push_back(std::move(segment));
  }

 private:
  // Lock-ins at the table's revolution frequency for each gyro whose axis is the table axis.
  void MeasureRippleOfSegment(int index,
                              const std::vector<const calib::ImuSample*>& rows,
                              const std::vector<double>& t,
                              const Eigen::Vector3d& w_B_dps) {
    std::vector<double> y(rows.size());
    for (int g = 0; g < 3; ++g) {
      if (std::abs(w_B_dps[g]) < 0.5 * w_B_dps.norm() || w_B_dps[g] == 0.0) continue;
      for (size_t i = 0; i < rows.size(); ++i) y[i] = Output(*rows[i], 6 + g);  // gx, gy, gz
      if (std::optional<RippleSegment> r = MeasureRipple(index, w_B_dps[g], t, y))
        data_->ripple[g].push_back(*r);
    }
  }

  // Gaps of the packet counter against its most frequent step in the segment (1, or log_every).
  void CountSequenceGaps(const std::vector<const calib::ImuSample*>& rows) {
    std::array<int, 256> steps{};
    for (size_t i = 1; i < rows.size(); ++i)
      ++steps[static_cast<uint8_t>(rows[i]->seq - rows[i - 1]->seq)];
    const int usual =
        static_cast<int>(std::max_element(steps.begin(), steps.end()) - steps.begin());
    if (usual == 0) return;
    for (size_t i = 1; i < rows.size(); ++i) {
      const int d = static_cast<uint8_t>(rows[i]->seq - rows[i - 1]->seq);
      if (d == usual) continue;
      const int missing = d > usual ? (d - usual) / usual : 0;
      ++data_->seq_gaps;
      data_->seq_missing += missing;
      if (missing > data_->largest_seq_gap) {
        data_->largest_seq_gap = missing;
        data_->largest_seq_gap_at_s = rows[i]->t_s;
      }
    }
  }

  void AddCell(int segment,
               const std::vector<const calib::ImuSample*>& rows,
               size_t begin,
               size_t end,
               const Eigen::Vector3d& f_B_g,
               const Eigen::Vector3d& w_B_dps) {
    DiagnosisCell c;
    c.segment = segment;
    c.run = rows[begin]->run;
    c.rows = static_cast<int>(end - begin);
    c.t_first_s = rows[begin]->t_s;
    c.t_last_s = rows[end - 1]->t_s;
    c.f_B_g = f_B_g;
    c.w_B_dps = w_B_dps;
    const double n = static_cast<double>(c.rows);
    for (int ch = 0; ch < kImuChannels; ++ch) {
      // Welford's update: the gyro counts sit near 4.2e6, so a plain sum of squares would cancel.
      double mean = 0.0, m2 = 0.0;
      for (size_t i = begin; i < end; ++i) {
        const double y = Output(*rows[i], ch);
        const double k = static_cast<double>(i - begin + 1);
        const double d = y - mean;
        mean += d / k;
        m2 += d * (y - mean);
      }
      c.y_mean[ch] = mean;
      c.y_var[ch] = c.rows > 1 ? m2 / (n - 1.0) : 0.0;
    }
    for (size_t i = begin; i < end; ++i) {
      c.t_mean_s += rows[i]->t_s / n;
      c.chamber_c += rows[i]->chamber_c / n;
      for (int k = 0; k < 3; ++k) c.temp_cnt_mean[k] += rows[i]->raw.temp_cnt[k] / n;
    }
    data_->cells.push_back(c);
  }

  DiagnosisData* data_;
  double cell_s_;
  double frame_period_s_;
};

const char* TrendName(calib::ThermalSegment s) {
  switch (s) {
    case calib::ThermalSegment::kUpRamp:
      return "up-ramp";
    case calib::ThermalSegment::kDownRamp:
      return "down-ramp";
    case calib::ThermalSegment::kSoak:
      return "soak";
  }
  return "?";
}

const char* TrendKind(calib::ThermalSegment s) {
  switch (s) {
    case calib::ThermalSegment::kUpRamp:
      return "thermal_up";
    case calib::ThermalSegment::kDownRamp:
      return "thermal_down";
    case calib::ThermalSegment::kSoak:
      return "thermal_soak";
  }
  return "?";
}

void CutThermal(const calib::ImuUnitData& unit, double g_scale, CellCutter* cutter) {
  const Eigen::Vector3d f = Up(unit.thermal_orientation) * g_scale;
  std::vector<const calib::ImuSample*> rows;
  int count = 0;
  for (size_t i = 0; i < unit.thermal.size(); ++i) {
    rows.push_back(&unit.thermal[i]);
    const bool last = i + 1 == unit.thermal.size();
    if (last || unit.thermal_segment[i + 1] != unit.thermal_segment[i] ||
        unit.thermal[i + 1].run != unit.thermal[i].run) {
      DiagnosisSegment s;
      s.run = unit.thermal[i].run;
      s.kind = TrendKind(unit.thermal_segment[i]);
      s.orientation = unit.thermal_orientation;
      s.label =
          fmt::format("run {} thermal {} {}", s.run, TrendName(unit.thermal_segment[i]), ++count);
      cutter->Segment(std::move(s), rows, f, Eigen::Vector3d::Zero());
      rows.clear();
    }
  }
}

void CutAcquisitions(const std::vector<calib::ImuAcquisition>& acquisitions,
                     double g_scale,
                     CellCutter* cutter) {
  for (const calib::ImuAcquisition& a : acquisitions) {
    if (a.samples.empty()) continue;
    std::vector<const calib::ImuSample*> rows;
    for (const calib::ImuSample& s : a.samples) rows.push_back(&s);
    std::stable_sort(
        rows.begin(), rows.end(), [](const calib::ImuSample* x, const calib::ImuSample* y) {
          return x->t_s < y->t_s;
        });
    DiagnosisSegment s;
    s.run = a.samples.front().run;
    s.step = a.step;
    s.kind = a.step_kind;
    s.orientation = a.orientation;
    s.rate_dps = a.rate_dps;
    s.label =
        fmt::format("run {} step {} {} orientation {}", s.run, a.step, a.step_kind, a.orientation);
    if (a.rate_dps != 0.0) s.label += fmt::format(" rate {:.1f} dps", a.rate_dps);
    const Eigen::Vector3d up = Up(a.orientation);
    cutter->Segment(std::move(s), rows, up * g_scale, up * a.rate_dps);
  }
}

// Least-squares slope of value(t) over the cells of one run within +-window/2 of each cell,
// never across a gap longer than kMaxTrendGap_s. `order` lists the run's cells by time.
std::vector<double> WindowSlopes(const std::vector<DiagnosisCell>& cells,
                                 const std::vector<int>& order,
                                 int sensor) {
  std::vector<double> slope(order.size(), 0.0);
  size_t lo = 0, hi = 0;
  for (size_t i = 0; i < order.size(); ++i) {
    const double t = cells[order[i]].t_mean_s;
    if (i > 0 && t - cells[order[i - 1]].t_mean_s > kMaxTrendGap_s) lo = hi = i;
    if (hi < i) hi = i;
    while (cells[order[lo]].t_mean_s < t - kRateWindow_s / 2) ++lo;
    while (hi + 1 < order.size() && cells[order[hi + 1]].t_mean_s <= t + kRateWindow_s / 2 &&
           cells[order[hi + 1]].t_mean_s - cells[order[hi]].t_mean_s <= kMaxTrendGap_s) {
      ++hi;
    }
    double sw = 0, st = 0, sv = 0, stt = 0, stv = 0;
    for (size_t j = lo; j <= hi; ++j) {
      const DiagnosisCell& c = cells[order[j]];
      const double w = c.rows, dt = c.t_mean_s - t, v = c.temp_cnt_mean[sensor];
      sw += w;
      st += w * dt;
      sv += w * v;
      stt += w * dt * dt;
      stv += w * dt * v;
    }
    const double den = sw * stt - st * st;
    if (hi > lo && den > 0.0) slope[i] = (sw * stv - st * sv) / den;
  }
  return slope;
}

ThermometerMap FitThermometer(const std::vector<DiagnosisCell>& cells,
                              const std::vector<double>& slope_cnt_per_s,
                              int sensor) {
  const double still = kTrendThreshold_c_per_s * kDatasheetTempCountsPerC;
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, lo = 1e9, hi = -1e9;
  double all_w = 0, all_x = 0, all_y = 0;
  for (size_t i = 0; i < cells.size(); ++i) {
    const double w = cells[i].rows, x = cells[i].chamber_c, y = cells[i].temp_cnt_mean[sensor];
    all_w += w;
    all_x += w * x;
    all_y += w * y;
    if (std::abs(slope_cnt_per_s[i]) > still) continue;
    sw += w;
    sx += w * x;
    sy += w * y;
    sxx += w * x * x;
    sxy += w * x * y;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  ThermometerMap map;
  if (hi - lo >= kMinFittedSpan_c && sw > 0) {
    map.slope_cnt_per_c = (sw * sxy - sx * sy) / (sw * sxx - sx * sx);
    map.offset_cnt = (sy - map.slope_cnt_per_c * sx) / sw;
    map.fitted = true;
  } else {
    map.offset_cnt = (all_y - map.slope_cnt_per_c * all_x) / all_w;
  }
  return map;
}

void DeriveThermalState(DiagnosisData* data) {
  std::vector<DiagnosisCell>& cells = data->cells;
  std::array<std::vector<double>, 3> slope_cnt;
  for (auto& s : slope_cnt) s.assign(cells.size(), 0.0);
  int runs = 0;
  for (const DiagnosisCell& c : cells) runs = std::max(runs, c.run + 1);
  std::vector<std::vector<int>> by_run(static_cast<size_t>(runs));
  for (size_t i = 0; i < cells.size(); ++i)
    by_run[static_cast<size_t>(cells[i].run)].push_back(static_cast<int>(i));
  for (std::vector<int>& order : by_run) {
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return cells[a].t_mean_s < cells[b].t_mean_s;
    });
    for (int k = 0; k < 3; ++k) {
      const std::vector<double> s = WindowSlopes(cells, order, k);
      for (size_t i = 0; i < order.size(); ++i) slope_cnt[k][order[i]] = s[i];
    }
  }
  for (int k = 0; k < 3; ++k) data->thermometers[k] = FitThermometer(cells, slope_cnt[k], k);
  double lo = 1e9, hi = -1e9;
  for (size_t i = 0; i < cells.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const ThermometerMap& m = data->thermometers[k];
      cells[i].temp_c[k] = m.ToC(cells[i].temp_cnt_mean[k]);
      cells[i].dtemp_dt_c_per_s[k] = slope_cnt[k][i] / m.slope_cnt_per_c;
    }
    lo = std::min(lo, cells[i].temp_c[0]);
    hi = std::max(hi, cells[i].temp_c[0]);
  }
  data->temp_span_c = hi - lo;
  for (const std::vector<int>& order : by_run) {
    if (order.empty()) continue;
    const double t0 = cells[order.front()].t_first_s;
    std::array<LastChangeSense, 3> sense;
    for (int i : order) {
      cells[i].t_since_start_s = cells[i].t_mean_s - t0;
      for (int k = 0; k < 3; ++k) cells[i].last_change_sense[k] = sense[k].Next(cells[i].temp_c[k]);
    }
  }
}

// The recording's row interval: the median over the first rows of each source.
// The unit's frame period from its packet counter: the time over the frames counted between
// consecutive rows less than 2.56 s apart (where the 8-bit counter cannot have turned), over the
// thermal rows and the acquisitions. Arrival times jitter by bursts; their sum over millions of
// frames does not. 0 when the counter never moves (a recording without one).
double FramePeriod(const calib::ImuUnitData& unit) {
  double frames = 0.0, time_s = 0.0;
  auto add = [&](const std::vector<calib::ImuSample>& rows) {
    for (size_t i = 1; i < rows.size(); ++i) {
      const int d = static_cast<uint8_t>(rows[i].seq - rows[i - 1].seq);
      const double dt = rows[i].t_s - rows[i - 1].t_s;
      if (d == 0 || dt < 0.0 || dt > 2.56) continue;
      frames += d;
      time_s += dt;
    }
  };
  add(unit.thermal);
  for (const auto* group : {&unit.accel, &unit.gyro, &unit.cross_axis}) {
    for (const calib::ImuAcquisition& a : *group) add(a.samples);
  }
  return frames > 0.0 ? time_s / frames : 0.0;
}

// The most frequent step of the packet counter between consecutive thermal rows (1, or log_every).
int UsualCounterStep(const calib::ImuUnitData& unit) {
  std::array<int, 256> steps{};
  for (size_t i = 1; i < unit.thermal.size(); ++i)
    ++steps[static_cast<uint8_t>(unit.thermal[i].seq - unit.thermal[i - 1].seq)];
  for (const auto* group : {&unit.accel, &unit.gyro, &unit.cross_axis}) {
    for (const calib::ImuAcquisition& a : *group) {
      for (size_t i = 1; i < a.samples.size(); ++i)
        ++steps[static_cast<uint8_t>(a.samples[i].seq - a.samples[i - 1].seq)];
    }
  }
  return static_cast<int>(std::max_element(steps.begin() + 1, steps.end()) - steps.begin());
}

double NominalInterval(const calib::ImuUnitData& unit) {
  constexpr size_t kLook = 20000;
  std::vector<double> times;
  for (size_t i = 0; i < std::min(kLook, unit.thermal.size()); ++i)
    times.push_back(unit.thermal[i].t_s);
  double d = MedianInterval(times);
  for (const auto* group : {&unit.accel, &unit.gyro, &unit.cross_axis}) {
    for (const calib::ImuAcquisition& a : *group) {
      if (d > 0.0) return d;
      times.clear();
      for (size_t i = 0; i < std::min(kLook, a.samples.size()); ++i)
        times.push_back(a.samples[i].t_s);
      d = MedianInterval(times);
    }
  }
  return d;
}

// One tick over the mean captured period for the duty outputs, one count for the gyros.
std::array<double, kImuChannels> OutputQuantum(const calib::ImuUnitData& unit) {
  constexpr size_t kLook = 20000;
  std::array<double, 6> t2_sum{};
  size_t n = 0;
  auto add = [&](const std::vector<calib::ImuSample>& rows) {
    for (size_t i = 0; i < rows.size() && n < kLook; ++i, ++n) {
      for (int ch = 0; ch < 6; ++ch) t2_sum[ch] += rows[i].raw.t2_cnt[ch];
    }
  };
  add(unit.thermal);
  for (const calib::ImuAcquisition& a : unit.accel) add(a.samples);
  std::array<double, kImuChannels> q{};
  for (int ch = 0; ch < kImuChannels; ++ch) {
    q[ch] = common::IsGyroChannel(ch) || n == 0 ? 1.0 : static_cast<double>(n) / t2_sum[ch];
  }
  return q;
}

}  // namespace

DiagnosisData BuildDiagnosisData(const calib::ImuUnitData& unit,
                                 double g_local_mps2,
                                 double cell_duration_s) {
  DiagnosisData data;
  data.serial = unit.serial;
  const double g_scale = g_local_mps2 / 9.80665;
  const double frame_period_s = FramePeriod(unit);
  const double row_interval_s =
      frame_period_s > 0.0 ? UsualCounterStep(unit) * frame_period_s : NominalInterval(unit);
  data.spectra = RowSpectra(kImuChannels, row_interval_s);
  data.slow_spectra =
      RowSpectra(kImuChannels, row_interval_s, kSpectrumWindowRows * kSlowWindowFactor);
  CellCutter cutter(&data, cell_duration_s, frame_period_s);
  CutThermal(unit, g_scale, &cutter);
  CutAcquisitions(unit.accel, g_scale, &cutter);
  CutAcquisitions(unit.gyro, g_scale, &cutter);
  CutAcquisitions(unit.cross_axis, g_scale, &cutter);
  if (data.segments.size() < 2) {
    throw calib::ImuInputError(
        unit.serial + ": " + std::to_string(data.segments.size()) +
        " segment(s) of calibration data; diagnosis needs at least 2 to hold one out");
  }
  DeriveThermalState(&data);
  data.output_quantum = OutputQuantum(unit);
  return data;
}

}  // namespace adahrs::diagnosis
