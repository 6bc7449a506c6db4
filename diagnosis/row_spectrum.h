// Row-level spectra of a recording's raw outputs, for periodic structure that 1 s cells average
// away (interference from a supply, a fan, a table's drive), located and never fitted.
// Each segment is cut into windows of `window_rows` consecutive rows at the recording's sample
// interval (a gap, or an interval off by more than 10 %, closes a window); each window is
// detrended (least-squares line), Hann-weighted and transformed, and its periodogram is added to
// the channel's and the segment's sums. Power per bin is |X_k|^2 / (N sum w^2): white noise of
// variance s^2 gives s^2 / N per bin, and a sinusoid of amplitude A puts A^2 / 4 into the bins
// of its positive-frequency lobe. Units: the raw output's, squared.
// A line is a bin whose log power stands above a floor fitted to its neighbours' (a quadratic in
// ln(frequency), so flicker or a filter's roll-off is not a line) by more than the channel's own
// robust spread of that excess times a normal quantile, Bonferroni-divided over the bins tested.
// Windows kSlowWindowFactor times longer carry the band below kMinLineBin (docs/diagnose.md
// "Method (IMU)", item 6).
// Not done: windows across a gap, lines below kMinLineBin bins (those are drift, not tones).
#pragma once

#include <string>
#include <vector>

namespace adahrs::diagnosis {

inline constexpr int kSpectrumWindowRows = 512;
inline constexpr int kMinLineBin = 6;
inline constexpr int kSlowWindowFactor = 8;

class RowSpectra {
 public:
  RowSpectra(int channels, double dt_s, int window_rows = kSpectrumWindowRows);

  /// Adds the rows of one segment: `time_s(i)` and `value(i, channel)` for i < rows, time order.
  template <typename Time, typename Value>
  void AddSegment(int segment, size_t rows, const Time& time_s, const Value& value);

  int channels() const { return channels_; }
  int window_rows() const { return window_rows_; }
  int bins() const { return window_rows_ / 2 + 1; }
  double dt_s() const { return dt_s_; }
  double BinHz(double bin) const { return bin / (window_rows_ * dt_s_); }
  int windows() const { return windows_; }
  /// Mean periodogram of the channel over every window (empty when there is none).
  std::vector<double> MeanPower(int channel) const;
  int segment_windows(int segment) const;
  /// Mean periodogram of the channel over one segment's windows.
  std::vector<double> SegmentPower(int segment, int channel) const;
  /// Every segment that holds at least one window.
  std::vector<int> SegmentsWithWindows() const;

 private:
  void AddWindow(int segment, const std::vector<double>& y_by_channel);
  void Grow(int segment);

  int channels_;
  double dt_s_;
  int window_rows_;
  int windows_ = 0;
  std::vector<double> window_;                // Hann weights
  std::vector<double> sum_;                   // channels x bins
  std::vector<int> segment_windows_;          // per segment
  std::vector<std::vector<double>> segment_;  // per segment: channels x bins
};

/// One periodic line of a channel: raw units.
struct PeriodicLine {
  double frequency_hz = 0.0;
  double amplitude = 0.0;     ///< of the sinusoid, raw output units
  double floor_ratio = 0.0;   ///< peak bin power over the fitted floor
  double z = 0.0;             ///< excess in the channel's robust spreads
  std::vector<int> segments;  ///< segments whose own windows show it (excess > 3 of their SE)
  int segments_with_windows = 0;
};

/// Lines of one channel at level `alpha` over its bins kMinLineBin ... `max_bin` (0: up to the
/// last below Nyquist), strongest first, at most `max_lines`. The lobes of the lines at
/// `known_hz` (found by other windows) are left out of the search and of every floor.
std::vector<PeriodicLine> FindPeriodicLines(const RowSpectra& spectra,
                                            int channel,
                                            double alpha,
                                            int max_lines = 5,
                                            int max_bin = 0,
                                            const std::vector<double>& known_hz = {});

/// The bins a search of FindPeriodicLines tests (0 when the spectra have no window).
int TestedBins(const RowSpectra& spectra, int max_bin = 0);

/// The median interval between consecutive times that are increasing (0 when there is none).
double MedianInterval(const std::vector<double>& times_s);

template <typename Time, typename Value>
void RowSpectra::AddSegment(int segment, size_t rows, const Time& time_s, const Value& value) {
  const size_t n = static_cast<size_t>(window_rows_);
  if (!(dt_s_ > 0.0) || rows < n) return;
  std::vector<double> y(n * static_cast<size_t>(channels_));
  size_t begin = 0;
  while (begin + n <= rows) {
    size_t end = begin + 1;
    while (end < begin + n) {
      const double dt = time_s(end) - time_s(end - 1);
      if (dt < 0.9 * dt_s_ || dt > 1.1 * dt_s_) break;
      ++end;
    }
    if (end < begin + n) {
      begin = end;  // the interval before `end` is off: the next window starts at it
      continue;
    }
    for (size_t i = 0; i < n; ++i) {
      for (int c = 0; c < channels_; ++c) y[static_cast<size_t>(c) * n + i] = value(begin + i, c);
    }
    AddWindow(segment, y);
    begin += n;
  }
}

}  // namespace adahrs::diagnosis
