#include "diagnosis/structure_location.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "common/imu_layout.h"
#include "common/median.h"
#include "diagnosis/row_spectrum.h"

namespace adahrs::diagnosis {
namespace {

constexpr double kOutlierRobustZ = 10.0;
constexpr double kOutlierNoiseZ = 6.0;
constexpr double kStepZ = 10.0;
constexpr int kStepWindowCells = 30;

}  // namespace

void LocateStructure(const DiagnosisData& data,
                     int ch,
                     const std::vector<double>& residual,
                     double phys,
                     const std::string& unit,
                     std::vector<Unexplained>* out) {
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
  for (size_t s = 0; s < segs; ++s) {
    const std::vector<double>& r = series[s];
    const int n = static_cast<int>(r.size());
    const int L = kStepWindowCells;
    if (n < 4 * L) continue;
    // d_i: mean of the next L cells minus mean of the previous L. Its robust spread over the
    // segment holds whatever wander the residual has (gyro bias flicker), so only a change far
    // beyond the segment's own wander counts as a step.
    std::vector<double> d;
    double left = std::accumulate(r.begin(), r.begin() + L, 0.0);
    double right = std::accumulate(r.begin() + L, r.begin() + 2 * L, 0.0);
    for (int i = L; i + L <= n; ++i) {
      if (i > L) {
        left += r[i - 1] - r[i - 1 - L];
        right += r[i + L - 1] - r[i - 1];
      }
      d.push_back((right - left) / L);
    }
    const double d_med = common::Median(d);
    std::vector<double> dev_d;
    for (double v : d) dev_d.push_back(std::abs(v - d_med));
    const double spread = 1.4826 * common::Median(dev_d);
    std::vector<double> diff;
    for (int i = 1; i < n; ++i) diff.push_back(std::abs(r[i] - r[i - 1]));
    const double white = 1.4826 * common::Median(diff) / std::sqrt(2.0) * std::sqrt(2.0 / L);
    size_t at = 0;
    for (size_t i = 0; i < d.size(); ++i) {
      if (std::abs(d[i] - d_med) > std::abs(d[at] - d_med)) at = i;
    }
    const double z = spread > 0.0 ? std::abs(d[at] - d_med) / spread : 0.0;
    if (z > kStepZ && std::abs(d[at]) > kOutlierNoiseZ * white) {
      double t_at = 0.0;
      int k = 0;
      for (const DiagnosisCell& c : data.cells) {
        if (c.segment == static_cast<int>(s) && k++ == static_cast<int>(at) + L) t_at = c.t_first_s;
      }
      out->push_back(
          {common::kImuChannelNames[ch],
           fmt::format("{} at t = {:.1f} s", data.segments[s].label, t_at),
           fmt::format("a step of {:+.3g} {} ({:.0f} times the segment's own wander over {} s); no "
                       "candidate term explains it",
                       d[at] * phys,
                       unit,
                       z,
                       L),
           d[at] * phys,
           unit});
    }
  }
}

void LocatePeriodic(const DiagnosisData& data,
                    int ch,
                    double alpha,
                    double phys,
                    const std::string& unit,
                    std::vector<Unexplained>* out,
                    std::vector<std::string>* notes) {
  const bool gyro = common::IsGyroChannel(ch);
  const double raw_scale = gyro ? 1.0 : 1e6;  // counts, or duty in ppm
  const char* raw_unit = gyro ? "counts" : "ppm of duty";
  for (const PeriodicLine& line : FindPeriodicLines(data.spectra, ch, alpha)) {
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
                                    data.spectra.window_rows());
    if (!line.segments.empty())
      where += fmt::format(", first {}", data.segments[line.segments.front()].label);
    out->push_back({common::kImuChannelNames[ch],
                    where,
                    what + "; no candidate term explains it",
                    line.amplitude * phys,
                    unit});
  }
}

}  // namespace adahrs::diagnosis
