#include "diagnosis/row_spectrum.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include <Eigen/Dense>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/special_functions/digamma.hpp>
#include <unsupported/Eigen/FFT>

#include "common/median.h"

namespace adahrs::diagnosis {
namespace {

constexpr int kFloorHalfWidth = 12;    // neighbours each side that carry the floor
constexpr int kLobeHalfWidth = 2;      // a Hann line's main lobe, bins each side
constexpr int kMinSideNeighbours = 3;  // for a quadratic floor, on each side of the bin
constexpr double kSegmentZ = 3.0;

// Log floor at each bin: a quadratic in ln(bin) fitted to the log power of the neighbours
// within kFloorHalfWidth, the bin's own lobe left out (a power law, flicker or a filter's
// roll-off, is a line in these coordinates). A real series' periodogram is even about the
// Nyquist bin, so neighbours beyond it are their mirror images; below bin 1 there are none.
// Masked bins (lines already found) carry no floor: a strong line would bend the quadratic.
std::vector<double> LogFloor(const std::vector<double>& log_p,
                             const std::vector<bool>& masked,
                             int first,
                             int last) {
  const int nyquist = static_cast<int>(log_p.size()) - 1;
  std::vector<double> floor(log_p.size(), 0.0);
  for (int k = first; k <= last; ++k) {
    Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
    Eigen::Vector3d atb = Eigen::Vector3d::Zero();
    int below = 0, above = 0;
    for (int j = std::max(1, k - kFloorHalfWidth); j <= k + kFloorHalfWidth; ++j) {
      if (std::abs(j - k) <= kLobeHalfWidth) continue;
      const int mirrored = j > nyquist ? 2 * nyquist - j : j;
      if (masked[static_cast<size_t>(mirrored)]) continue;
      const double x = std::log(static_cast<double>(j) / k);
      const Eigen::Vector3d a(1.0, x, x * x);
      ata += a * a.transpose();
      atb += a * log_p[static_cast<size_t>(mirrored)];
      ++(j < k ? below : above);
    }
    // With neighbours on one side only (lines masked next to the lowest bins) a quadratic would
    // be extrapolated: a line in ln(frequency) is.
    const int terms = below < kMinSideNeighbours || above < kMinSideNeighbours ? 2 : 3;
    floor[static_cast<size_t>(k)] =
        ata.topLeftCorner(terms, terms).ldlt().solve(atb.head(terms))[0];
  }
  return floor;
}

}  // namespace

RowSpectra::RowSpectra(int channels, double dt_s, int window_rows)
    : channels_(channels), dt_s_(dt_s), window_rows_(window_rows) {
  window_.resize(static_cast<size_t>(window_rows_));
  for (int i = 0; i < window_rows_; ++i) {
    window_[static_cast<size_t>(i)] =
        0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * i / window_rows_);
  }
  sum_.assign(static_cast<size_t>(channels_ * bins()), 0.0);
}

void RowSpectra::Grow(int segment) {
  if (segment < static_cast<int>(segment_.size())) return;
  segment_.resize(static_cast<size_t>(segment) + 1);
  segment_windows_.resize(static_cast<size_t>(segment) + 1, 0);
}

void RowSpectra::AddWindow(int segment, const std::vector<double>& y_by_channel) {
  Grow(segment);
  std::vector<double>& seg = segment_[static_cast<size_t>(segment)];
  if (seg.empty()) seg.assign(sum_.size(), 0.0);
  const int n = window_rows_;
  const double mean_i = (n - 1) / 2.0;
  double sxx = 0.0, sw2 = 0.0;
  for (int i = 0; i < n; ++i) sxx += (i - mean_i) * (i - mean_i);
  for (double w : window_) sw2 += w * w;
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
  std::vector<double> x(static_cast<size_t>(n));
  std::vector<std::complex<double>> spectrum;
  for (int c = 0; c < channels_; ++c) {
    const double* y = y_by_channel.data() + static_cast<size_t>(c) * static_cast<size_t>(n);
    // Detrend about the window's first value: gyro counts sit near 4.2e6.
    double sy = 0.0, sxy = 0.0;
    for (int i = 0; i < n; ++i) {
      const double v = y[i] - y[0];
      sy += v;
      sxy += (i - mean_i) * v;
    }
    const double slope = sxy / sxx, mean = sy / n;
    for (int i = 0; i < n; ++i) {
      x[static_cast<size_t>(i)] =
          (y[i] - y[0] - mean - slope * (i - mean_i)) * window_[static_cast<size_t>(i)];
    }
    fft.fwd(spectrum, x);
    const size_t base = static_cast<size_t>(c * bins());
    for (int k = 0; k < bins(); ++k) {
      const double p = std::norm(spectrum[static_cast<size_t>(k)]) / (n * sw2);
      sum_[base + static_cast<size_t>(k)] += p;
      seg[base + static_cast<size_t>(k)] += p;
    }
  }
  ++windows_;
  ++segment_windows_[static_cast<size_t>(segment)];
}

std::vector<double> RowSpectra::MeanPower(int channel) const {
  if (windows_ == 0) return {};
  const auto first = sum_.begin() + channel * bins();
  std::vector<double> p(first, first + bins());
  for (double& v : p) v /= windows_;
  return p;
}

int RowSpectra::segment_windows(int segment) const {
  return segment < static_cast<int>(segment_windows_.size())
             ? segment_windows_[static_cast<size_t>(segment)]
             : 0;
}

std::vector<double> RowSpectra::SegmentPower(int segment, int channel) const {
  const int m = segment_windows(segment);
  if (m == 0) return {};
  const auto first = segment_[static_cast<size_t>(segment)].begin() + channel * bins();
  std::vector<double> p(first, first + bins());
  for (double& v : p) v /= m;
  return p;
}

std::vector<int> RowSpectra::SegmentsWithWindows() const {
  std::vector<int> out;
  for (size_t s = 0; s < segment_windows_.size(); ++s) {
    if (segment_windows_[s] > 0) out.push_back(static_cast<int>(s));
  }
  return out;
}

namespace {

// The floor and each bin's excess over it in the channel's robust spreads, lines in `masked` left
// out of both.
struct Excess {
  std::vector<double> floor;  ///< log power
  std::vector<double> z;      ///< per bin; 0 outside [first, last] and on masked bins
  bool ok = false;
};

Excess ExcessOverFloor(const std::vector<double>& log_p,
                       const std::vector<bool>& masked,
                       int first,
                       int last) {
  Excess out;
  out.floor = LogFloor(log_p, masked, first, last);
  std::vector<double> excess;
  for (int k = first; k <= last; ++k) {
    if (!masked[static_cast<size_t>(k)])
      excess.push_back(log_p[static_cast<size_t>(k)] - out.floor[static_cast<size_t>(k)]);
  }
  const double med = common::Median(excess);
  std::vector<double> dev;
  for (double e : excess) dev.push_back(std::abs(e - med));
  const double spread = 1.4826 * common::Median(dev);
  out.z.assign(log_p.size(), 0.0);
  if (!(spread > 0.0)) return out;
  for (int k = first; k <= last; ++k) {
    if (!masked[static_cast<size_t>(k)]) {
      out.z[static_cast<size_t>(k)] =
          (log_p[static_cast<size_t>(k)] - out.floor[static_cast<size_t>(k)] - med) / spread;
    }
  }
  out.ok = true;
  return out;
}

}  // namespace

std::vector<PeriodicLine> FindPeriodicLines(const RowSpectra& spectra,
                                            int channel,
                                            double alpha,
                                            int max_lines,
                                            int max_bin,
                                            const std::vector<double>& known_hz) {
  const std::vector<double> p = spectra.MeanPower(channel);
  int last = spectra.bins() - 2;  // the Nyquist bin is left out
  if (max_bin > 0) last = std::min(last, max_bin);
  if (p.empty() || last < kFloorHalfWidth) return {};
  std::vector<double> log_p(p.size());
  for (size_t k = 0; k < p.size(); ++k) log_p[k] = std::log(std::max(p[k], 1e-300));
  const boost::math::normal normal;
  const double tested = last - kMinLineBin + 1;
  const double z_crit = boost::math::quantile(boost::math::complement(normal, alpha / tested));
  // The log of a mean of m periodograms sits below the log of its expectation by psi(m) - ln m.
  const double m = spectra.windows();
  const double log_bias = boost::math::digamma(m) - std::log(m);

  std::vector<bool> masked(p.size(), false);
  for (double f : known_hz) {
    const int k = static_cast<int>(std::lround(f / spectra.BinHz(1.0)));
    for (int j = k - kLobeHalfWidth; j <= k + kLobeHalfWidth; ++j) {
      if (j >= 0 && j < static_cast<int>(masked.size())) masked[static_cast<size_t>(j)] = true;
    }
  }
  std::vector<PeriodicLine> lines;
  while (static_cast<int>(lines.size()) < max_lines) {
    const Excess ex = ExcessOverFloor(log_p, masked, kMinLineBin, last);
    if (!ex.ok) break;
    int best = -1;
    double best_z = z_crit;
    for (int k = kMinLineBin; k <= last; ++k) {
      if (ex.z[static_cast<size_t>(k)] > best_z) {
        best = k;
        best_z = ex.z[static_cast<size_t>(k)];
      }
    }
    if (best < 0) break;
    const std::vector<double>& floor = ex.floor;
    const double level = std::exp(floor[static_cast<size_t>(best)] - log_bias);
    double power = 0.0, moment = 0.0;
    for (int j = std::max(1, best - kLobeHalfWidth); j <= std::min(last, best + kLobeHalfWidth);
         ++j) {
      const double e = std::max(0.0, p[static_cast<size_t>(j)] - level);
      power += e;
      moment += e * j;
    }
    PeriodicLine line;
    line.frequency_hz = spectra.BinHz(power > 0.0 ? moment / power : best);
    line.amplitude = 2.0 * std::sqrt(power);
    line.floor_ratio = p[static_cast<size_t>(best)] / level;
    line.z = best_z;
    for (int s : spectra.SegmentsWithWindows()) {
      const std::vector<double> ps = spectra.SegmentPower(s, channel);
      double sum = 0.0;
      for (int j = best - 1; j <= best + 1; ++j) sum += ps[static_cast<size_t>(j)] - level;
      // Adjacent Hann bins are correlated: the SE of a 3-bin sum is taken as 1.5 x independent.
      const double se = 1.5 * level * std::sqrt(3.0 / spectra.segment_windows(s));
      if (sum > kSegmentZ * se) line.segments.push_back(s);
      ++line.segments_with_windows;
    }
    lines.push_back(std::move(line));
    for (int j = best - kLobeHalfWidth; j <= best + kLobeHalfWidth; ++j) {
      if (j >= 0 && j < static_cast<int>(masked.size())) masked[static_cast<size_t>(j)] = true;
    }
  }
  return lines;
}

int TestedBins(const RowSpectra& spectra, int max_bin) {
  if (spectra.windows() == 0) return 0;
  int last = spectra.bins() - 2;
  if (max_bin > 0) last = std::min(last, max_bin);
  return std::max(0, last - kMinLineBin + 1);
}

double MedianInterval(const std::vector<double>& times_s) {
  std::vector<double> d;
  for (size_t i = 1; i < times_s.size(); ++i) {
    if (times_s[i] > times_s[i - 1]) d.push_back(times_s[i] - times_s[i - 1]);
  }
  return common::Median(d);
}

}  // namespace adahrs::diagnosis
