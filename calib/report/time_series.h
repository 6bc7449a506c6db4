// The report's time series (docs/report.md "Time series"): what the instruments and every unit
// did over the whole run, as the reference method's time plots show a run (Figs. 19-22, 65).
// Streamed row by row and decimated: each series keeps at most kTimeSeriesBins bins of its
// minimum and maximum (a bin's width doubles whenever the bins run out), drawn as the envelope
// they make, so a spike survives and a ten-million-row run gives a figure of a few thousand
// points. Figures: the instruments (chamber temperature; table rate or the test set's pressures)
// with a mark at each step's first row, then per unit its outputs: IMU gyro counts and
// accelerometer duty (T1/T2 - 0.5) from the raw fields in raw and thermal mode, the compensated
// values in sensor-calibrated mode (channels in g and deg/s) and fully calibrated mode (A in
// m/s^2, G in deg/s; compensated_frame.h); ADS bridge codes in raw mode, altitude and airspeed in
// surface mode.
// Left out: the rejected intervals (shown in the run summary), a time axis in wall-clock time.
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "hil/recording/recording_format.h"

namespace adahrs::calib {

/// Bins per series at most (twice as many points drawn).
inline constexpr size_t kTimeSeriesBins = 600;

/// Min/max decimation of one series against time.
class DecimatedSeries {
 public:
  void Add(double t_s, double value);
  /// The envelope: per bin (t, min), (t, max), in time order.
  void Envelope(std::vector<double>& t_s, std::vector<double>& value) const;
  bool empty() const { return bins_.empty(); }

 private:
  struct Bin {
    double t_s, lo, hi;
  };
  void Halve();
  double t0_s_ = 0.0;
  double width_s_ = 0.01;  // a packet period to start with
  std::vector<Bin> bins_;
};

/// Every figure of the run's time series, from its rows. A row costs no allocation once its
/// unit's figures exist: each (unit, layout) keeps the series its rows feed, in layout order.
class TimeSeriesAccumulator {
 public:
  void Add(const hil::ImuRecordRow& row);
  void Add(const hil::AdsRecordRow& row);
  /// The section body: the figures as inline SVG.
  std::string Figures() const;

  /// What a row feeds: its unit's outputs in one of the recording modes, or the instruments.
  enum class Layout {
    kImuInstruments,
    kAdsInstruments,
    kImuRaw,
    kImuMode2,
    kImuMode3,
    kAdsRaw,
    kAdsSurface
  };

 private:
  struct Figure {
    std::string title;
    std::string y_label;
    std::vector<std::string> labels;
    std::vector<DecimatedSeries> series;  // one per label; sized once
  };
  // The series one unit's rows of one layout feed, in the order the layout names them.
  struct Feed {
    std::string unit;
    Layout layout;
    std::vector<DecimatedSeries*> series;
  };
  Feed& FeedOf(const std::string& unit, Layout layout);
  void Step(double t_s, int step);

  std::deque<Figure> figures_;  // first-seen order; a deque keeps the series' addresses
  std::vector<Feed> feeds_;
  std::vector<double> step_starts_s_;
  int last_step_ = -1;
  std::string instrument_unit_;  // the unit whose rows carry the instrument readings
};

}  // namespace adahrs::calib
