#include "diagnosis/structure_location.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <optional>

#include <boost/math/distributions/normal.hpp>

#include <fmt/format.h>

#include "common/imu_layout.h"
#include "common/median.h"
#include "diagnosis/row_spectrum.h"

namespace adahrs::diagnosis {
namespace {

constexpr double kOutlierRobustZ = 10.0;
constexpr double kOutlierNoiseZ = 6.0;
constexpr int kStepWindowCells = 30;
/// The step rule's design false-alarm rate per channel and recording-hour (Gaussian contrasts).
constexpr double kStepFalseAlarmsPerHour = 1e-3;
/// How far the short contrast must stand out of its own spread to call the change abrupt.
constexpr double kShortStepZ = 3.0;
/// The standard normal quantile of 90 %: a step this many spreads beyond the threshold is
/// located with 90 % probability.
constexpr double kPowerZ90 = 1.2816;

// A step located in one segment's cell series: the cell it starts at, its size and how many
// spreads of the contrast it stands out.
struct LocatedStep {
  int cell = 0;
  double size = 0.0;
  double z = 0.0;
};

// One segment's scan: the contrast's spread, the z a step needs there, the step if one passed.
struct StepScan {
  double sigma = 0.0;
  double z_needed = 0.0;
  std::optional<LocatedStep> step;
};

// d_j: mean of the `window` cells from j + window on minus mean of the `window` before them.
std::vector<double> Contrast(const std::vector<double>& r, int window) {
  std::vector<double> d;
  const int n = static_cast<int>(r.size());
  if (n < 2 * window) return d;
  double left = std::accumulate(r.begin(), r.begin() + window, 0.0);
  double right = std::accumulate(r.begin() + window, r.begin() + 2 * window, 0.0);
  for (int i = window; i + window <= n; ++i) {
    if (i > window) {
      left += r[i - 1] - r[i - 1 - window];
      right += r[i + window - 1] - r[i - 1];
    }
    d.push_back((right - left) / window);
  }
  return d;
}

// Robust standard deviation about the median: 1.4826 x the median absolute deviation.
double RobustSpread(const std::vector<double>& v, double* median) {
  *median = common::Median(v);
  std::vector<double> dev;
  dev.reserve(v.size());
  for (double x : v) dev.push_back(std::abs(x - *median));
  return 1.4826 * common::Median(dev);
}

// The z a Gaussian contrast must exceed so that a segment of `cells` cells false-alarms at
// kStepFalseAlarmsPerHour: Bonferroni over cells / window independent contrasts, two-sided.
double StepThreshold(int cells, int window) {
  const double tests = std::max(1.0, static_cast<double>(cells) / window);
  const double alpha = kStepFalseAlarmsPerHour * cells * kCellDuration_s / 3600.0;
  const boost::math::normal normal;
  return boost::math::quantile(boost::math::complement(normal, alpha / (2.0 * tests)));
}

// The position nearest `cell` (within half a long window) where the short contrast peaks, and
// whether it holds at least half of `size` there and stands out of its own spread: a step keeps
// its size in a contrast of a fifth of the window, a bend's contrast shrinks with the window.
std::optional<int> AbruptAt(const std::vector<double>& r, int cell, double size) {
  const int Ls = kStepWindowCells / 5;
  const std::vector<double> ds = Contrast(r, Ls);
  double ds_med = 0.0;
  const double ds_spread = RobustSpread(ds, &ds_med);
  int best = -1;
  for (int j = cell - kStepWindowCells / 2 - Ls; j <= cell + kStepWindowCells / 2 - Ls; ++j) {
    if (j < 0 || j >= static_cast<int>(ds.size())) continue;
    if (best < 0 || std::abs(ds[j] - ds_med) > std::abs(ds[best] - ds_med)) best = j;
  }
  if (best < 0) return std::nullopt;
  const double short_size = ds[best] - ds_med;
  if (short_size * size <= 0.0 || std::abs(short_size) < 0.5 * std::abs(size) ||
      std::abs(short_size) <= kShortStepZ * ds_spread)
    return std::nullopt;
  return best + Ls;
}

// The robust spread of the 30-cell contrast over every long segment of one channel, each about
// its own median. A bias that flickers (1/f) has long memory: one segment's contrasts move
// together, so their own spread understates the channel's; the pooled one does not.
double PooledContrastSpread(const std::vector<std::vector<double>>& series) {
  std::vector<double> all;
  for (const std::vector<double>& r : series) {
    if (static_cast<int>(r.size()) < 4 * kStepWindowCells) continue;
    std::vector<double> d = Contrast(r, kStepWindowCells);
    const double med = common::Median(d);
    for (double v : d) all.push_back(v - med);
  }
  if (all.empty()) return 0.0;
  double med = 0.0;
  return RobustSpread(all, &med);
}

// The largest step of one segment's cell series and whether it passes (docs/diagnose.md "Method
// (IMU)", item 5). The spread of the contrast over the segment holds its white noise, its wander
// and flicker at the window's scale and any slow trend the model leaves; a step moves only 2L of
// the contrasts, so it barely moves their median absolute deviation.
std::optional<StepScan> ScanForStep(const std::vector<double>& r, double pooled_spread) {
  const int n = static_cast<int>(r.size());
  const int L = kStepWindowCells;
  if (n < 4 * L) return std::nullopt;
  const std::vector<double> d = Contrast(r, L);
  double d_med = 0.0;
  const double spread = RobustSpread(d, &d_med);
  std::vector<double> diff;
  for (int i = 1; i < n; ++i) diff.push_back(std::abs(r[i] - r[i - 1]));
  const double white = 1.4826 * common::Median(diff) / std::sqrt(2.0) * std::sqrt(2.0 / L);
  StepScan scan{std::max({spread, pooled_spread, white}), StepThreshold(n, L), std::nullopt};
  if (!(scan.sigma > 0.0)) return std::nullopt;
  size_t at = 0;
  for (size_t i = 0; i < d.size(); ++i) {
    if (std::abs(d[i] - d_med) > std::abs(d[at] - d_med)) at = i;
  }
  const LocatedStep step{
      static_cast<int>(at) + L, d[at] - d_med, std::abs(d[at] - d_med) / scan.sigma};
  if (step.z < scan.z_needed) return scan;
  if (const std::optional<int> abrupt = AbruptAt(r, step.cell, step.size)) {
    scan.step = step;
    scan.step->cell = *abrupt;
  }
  return scan;
}

// Periodic lines of channel `ch` in one band of the rows' spectra.
void LocatePeriodicInBand(const DiagnosisData& data,
                          const RowSpectra& spectra,
                          int max_bin,
                          int ch,
                          double alpha,
                          double phys,
                          const std::string& unit,
                          std::vector<Unexplained>* out,
                          std::vector<std::string>* notes,
                          std::vector<double>* found_hz) {
  const bool gyro = common::IsGyroChannel(ch);
  const double raw_scale = gyro ? 1.0 : 1e6;  // counts, or duty in ppm
  const char* raw_unit = gyro ? "counts" : "ppm of duty";
  const std::vector<double> known_hz = *found_hz;
  for (const PeriodicLine& line : FindPeriodicLines(spectra, ch, alpha, 5, max_bin, known_hz)) {
    found_hz->push_back(line.frequency_hz);
    const std::string what = fmt::format(
        "periodic {:.3g} Hz, amplitude {:.3g} {} ({:.3g} {}), {:.1f} times the noise floor at that "
        "frequency",
        line.frequency_hz,
        line.amplitude * raw_scale,
        raw_unit,
        line.amplitude * phys,
        unit,
        line.floor_ratio);
    if (line.amplitude < 0.5 * data.output_quantum[ch]) {
      notes->push_back(
          fmt::format("{}: {}: below half the output step ({:.3g} {}), capture quantisation",
                      common::kImuChannelNames[ch],
                      what,
                      data.output_quantum[ch] * raw_scale,
                      raw_unit));
      continue;
    }
    std::string where = fmt::format("rows of {} of {} segments with {}-row windows",
                                    line.segments.size(),
                                    line.segments_with_windows,
                                    spectra.window_rows());
    if (!line.segments.empty())
      where += fmt::format(", first {}", data.segments[line.segments.front()].label);
    out->push_back({common::kImuChannelNames[ch],
                    where,
                    what + "; no candidate term explains it",
                    line.amplitude * phys,
                    unit});
  }
}

// Steps of channel `ch` in each segment's cell series, and in `notes` the smallest step each
// segment would show with 90 % probability.
void LocateSteps(const DiagnosisData& data,
                 int ch,
                 const std::vector<std::vector<double>>& series,
                 double phys,
                 const std::string& unit,
                 std::vector<Unexplained>* out,
                 std::vector<std::string>* notes) {
  const double pooled = PooledContrastSpread(series);
  double min_limit = 0.0, max_limit = 0.0;
  size_t min_at = 0, max_at = 0;
  bool scanned = false;
  for (size_t s = 0; s < series.size(); ++s) {
    const std::optional<StepScan> scan = ScanForStep(series[s], pooled);
    if (!scan) continue;
    const double limit = (scan->z_needed + kPowerZ90) * scan->sigma;
    if (!scanned || limit < min_limit) std::tie(min_limit, min_at) = std::pair(limit, s);
    if (!scanned || limit > max_limit) std::tie(max_limit, max_at) = std::pair(limit, s);
    scanned = true;
    if (!scan->step) continue;
    const LocatedStep& step = *scan->step;
    double t_at = 0.0;
    int k = 0;
    for (const DiagnosisCell& c : data.cells) {
      if (c.segment == static_cast<int>(s) && k++ == step.cell) t_at = c.t_first_s;
    }
    out->push_back(
        {common::kImuChannelNames[ch],
         fmt::format("{} at t = {:.1f} s", data.segments[s].label, t_at),
         fmt::format("a step of {:+.3g} {} ({:.1f} times the spread of the segment's {} s "
                     "contrast, {:.1f} needed for {:g} false alarms per channel-hour); no "
                     "candidate term explains it",
                     step.size * phys,
                     unit,
                     step.z,
                     kStepWindowCells,
                     scan->z_needed,
                     kStepFalseAlarmsPerHour),
         step.size * phys,
         unit});
  }
  if (!scanned) return;
  notes->push_back(fmt::format(
      "{}: steps located with 90 % probability from {:.2g} {} ({}) to {:.2g} {} ({}), at {:g} "
      "false alarms per channel-hour",
      common::kImuChannelNames[ch],
      min_limit * phys,
      unit,
      data.segments[min_at].label,
      max_limit * phys,
      unit,
      data.segments[max_at].label,
      kStepFalseAlarmsPerHour));
}

}  // namespace

void LocateStructure(const DiagnosisData& data,
                     int ch,
                     const std::vector<double>& residual,
                     double phys,
                     const std::string& unit,
                     std::vector<Unexplained>* out,
                     std::vector<std::string>* notes) {
  const size_t segs = data.segments.size();
  std::vector<double> sum(segs, 0.0), w(segs, 0.0), var(segs, 0.0);
  std::vector<std::vector<double>> series(segs);
  for (size_t i = 0; i < data.cells.size(); ++i) {
    const DiagnosisCell& c = data.cells[i];
    sum[c.segment] += c.rows * residual[i];
    w[c.segment] += c.rows;
    var[c.segment] += c.y_var[ch] * c.rows;
    series[c.segment].push_back(residual[i]);
  }
  std::vector<double> mean(segs, 0.0);
  for (size_t s = 0; s < segs; ++s) mean[s] = w[s] > 0 ? sum[s] / w[s] : 0.0;
  const double med = common::Median(mean);
  std::vector<double> dev;
  for (double m : mean) dev.push_back(std::abs(m - med));
  const double robust = 1.4826 * common::Median(dev);
  for (size_t s = 0; s < segs; ++s) {
    if (!(w[s] > 0)) continue;
    const double white_se = std::sqrt(var[s] / w[s] / w[s]);
    const double d = mean[s] - med;
    if (std::abs(d) > kOutlierRobustZ * robust && std::abs(d) > kOutlierNoiseZ * white_se &&
        robust > 0.0) {
      out->push_back(
          {common::kImuChannelNames[ch],
           data.segments[s].label,
           fmt::format(
               "segment mean {:+.3g} {} away from the other segments' (robust spread {:.2g}); "
               "no candidate term explains it",
               d * phys,
               unit,
               robust * phys),
           d * phys,
           unit});
    }
  }
  LocateSteps(data, ch, series, phys, unit, out, notes);
}

void LocatePeriodic(const DiagnosisData& data,
                    int ch,
                    double alpha,
                    double phys,
                    const std::string& unit,
                    std::vector<Unexplained>* out,
                    std::vector<std::string>* notes) {
  // Two bands, the level shared in proportion to the bins each tests: the slow windows below the
  // rows' windows' kMinLineBin, then the rows' windows from there up, the slow band's lines
  // masked (their lobes would bend the short windows' floor near bin kMinLineBin).
  struct Band {
    const RowSpectra* spectra;
    int max_bin;
  };
  const Band bands[] = {{&data.slow_spectra, kSlowWindowFactor * kMinLineBin - 1},
                        {&data.spectra, 0}};
  std::vector<double> found_hz;
  double tested = 0.0;
  for (const Band& b : bands) tested += TestedBins(*b.spectra, b.max_bin);
  for (const Band& band : bands) {
    const double share = tested > 0.0 ? TestedBins(*band.spectra, band.max_bin) / tested : 0.0;
    if (!(share > 0.0)) continue;
    LocatePeriodicInBand(
        data, *band.spectra, band.max_bin, ch, alpha * share, phys, unit, out, notes, &found_hz);
  }
}

}  // namespace adahrs::diagnosis
