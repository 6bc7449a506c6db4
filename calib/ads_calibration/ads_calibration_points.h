// ADS calibration points from a recording: the rows of one unit whose TAG is a step's TAG
// (non-zero) and that lie outside every rejected interval of meta.json, averaged per step into
// one point of mean ADS1254 codes (static and pitot bridge outputs, bridge voltages, temperature
// signals), mean test-set pressures, chamber reading, and the reference altitude and calibrated
// airspeed by ISA (common/atmosphere.h, air_data.h), as the test set converts. Every point is an
// altitude point; airspeed points are those at or above kMinAirspeedPointKt.
// Units: codes in counts, pressures in Pa, altitude in ft, airspeed in kt, temperature in degC.
// Refusals (naming ads.csv, line and column): docs/calibration-strategies.md ("Calibration points
// from a recording").
// Left out: outlier rejection inside a step (the executor's rejected intervals do that), the test
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
