// ADS calibration points from a recording (docs/recording-format.md): the rows of one
// unit whose TAG is a step's TAG (non-zero) and that lie outside every rejected interval of
// meta.json are that step's calibration data; each step's rows are averaged into one point.
//
// Each point carries the mean ADS1254 codes (static and pitot bridge outputs and their bridge
// voltages, the sensors' temperature signals), the mean pressures the air data test set reported
// (ps_ref_pa, qc_ref_pa), the chamber reading, and the reference altitude and calibrated airspeed
// computed from those pressures by ISA (common/atmosphere.h, air_data.h): the standard
// formulas, as the test set itself converts. A point is an airspeed point when its impact pressure
// is above that of kMinAirspeedPointKt; every point is an altitude point (the static sensor reads
// its pressure whatever the pitot does).
// Refused, naming ads.csv, the line and the column: a non-finite reference or chamber value, a
// code at the converter's rail (saturated), a recording without rows of the unit, a reference
// pressure that moved more than kMaxReferenceSpanPa within one step's acquisition (the point's
// truth is then unknown: a test set still settling, or a stale reading on the first rows). Not
// modelled: outlier rejection inside a step (the executor's rejected intervals do that), the test
// set's own uncertainty (taken as exact).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "hil/recording/recording_reader.h"

namespace adahrs::calib {

/// Points whose reference CAS is below this carry no airspeed information (qc ~ 0).
inline constexpr double kMinAirspeedPointKt = 10.0;
/// Largest span of a reference pressure (static or impact) over one step's rows: four times the
/// largest seen in a steady acquisition (6.4 Pa over the 198 points of a demo run, 2026-11-23).
inline constexpr double kMaxReferenceSpanPa = 25.0;

struct AdsCalibrationPoint {
  int step = 0;
  uint8_t tag = 0;
  int rows = 0;                 ///< packets averaged
  int first_line = 0;           ///< ads.csv line of the first row (1 = header)
  double ps_cnt = 0.0;          ///< static bridge output, ADC code
  double pt_cnt = 0.0;          ///< pitot bridge output, ADC code
  double ps_temp_cnt = 0.0;     ///< static bridge voltage, ADC code
  double pt_temp_cnt = 0.0;     ///< pitot bridge voltage, ADC code
  double ps_ref_pa = 0.0;       ///< test set static pressure
  double qc_ref_pa = 0.0;       ///< test set impact pressure
  double chamber_c = 0.0;       ///< chamber reading
  double alt_ft = 0.0;          ///< ISA pressure altitude of ps_ref_pa
  double cas_kt = 0.0;          ///< ISA calibrated airspeed of qc_ref_pa
  bool airspeed_point = false;  ///< cas_kt >= kMinAirspeedPointKt
};

/// The selection one row at a time: Add every ads.csv row in file order with its CSV line, then
/// Points(). Holds one sum per step, never the rows.
class AdsPointSelector {
 public:
  /// `meta` is the run's meta.json (its rejected intervals); `source` is named in errors.
  AdsPointSelector(const hil::RecordingMeta& meta, std::string serial, std::string source);

  void Add(const hil::AdsRecordRow& row, int line);
  /// The points in step order; throws as SelectAdsCalibrationPoints does.
  std::vector<AdsCalibrationPoint> Points() const;

 private:
  struct Extremes {
    double min = 0, max = 0;
    int min_line = 0, max_line = 0;
    void Add(double v, int line, bool first);
  };
  struct Sum {
    AdsCalibrationPoint point;
    double ps = 0, pt = 0, ps_t = 0, pt_t = 0, ps_ref = 0, qc_ref = 0, chamber = 0;
    Extremes ps_ref_range, qc_ref_range;
  };

  std::string serial_;
  std::string source_;
  std::vector<hil::RejectedInterval> rejected_;
  std::map<int, Sum> by_step_;
  bool unit_seen_ = false;
};

/// The calibration points of unit `serial` in `recording` (read from `source`, named in errors),
/// in step order. Throws std::runtime_error naming file, line and column for bad input.
std::vector<AdsCalibrationPoint> SelectAdsCalibrationPoints(const hil::Recording& recording,
                                                            const std::string& serial,
                                                            const std::string& source);

/// The points of each of `serials` in one streamed pass over `run_dir` (hil::StreamRecording;
/// `source` is named in errors), as SelectAdsCalibrationPoints selects them.
std::map<std::string, std::vector<AdsCalibrationPoint>> StreamAdsCalibrationPoints(
    const std::filesystem::path& run_dir,
    const std::vector<std::string>& serials,
    const std::string& source);

}  // namespace adahrs::calib
