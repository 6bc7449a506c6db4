// The ADS parts of report.html for one unit: its constants with standard errors, the raw data
// (each bridge's mean code per calibration point against the test set's pressure, one series per
// chamber temperature, and the same less its straight line: the reference method's Figs. 16 and
// 24), the fitted surfaces' residual map (reference altitude or airspeed against chamber
// temperature, each point marked by its |residual| as a fraction of the tolerance there), and the
// error map over altitude x temperature (and airspeed x temperature) against the specification's
// tolerance envelope of the specification given (calib/acceptance/specification.h). References are
// the test set's pressures converted by the ISA (pressure altitude, ft) and the calibrated-airspeed
// formula (kt). Rows recorded in surface mode carry the unit's own values, averaged per acquisition
// (rows of one step and TAG at one test-set aim). Rows recorded raw are the fit's calibration
// points (ads_calibration_points.h: the same selection and refusals), evaluated with the double
// reference compensator and the file's constants at their mean codes, the hysteresis states those
// the fit regresses on (bridge_history.h); the figure says which. Rows in rejected intervals and
// rows with TAG 0 (between acquisitions) are left out.
#pragma once

#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "calib/acceptance/specification.h"
#include "calib/ads_calibration/ads_calibration_points.h"
#include "calib/constants/constants_file.h"
#include "hil/recording/recording_format.h"
#include "hil/recording/recording_meta.h"

namespace adahrs::calib {

/// The acquisitions of one unit, summed one row at a time: Add every ads.csv row in file order
/// (other units' rows are passed over), then Sections(). Holds one sum per acquisition.
class AdsReportAccumulator {
 public:
  /// `meta` supplies rejected intervals; `constants` may be null and must outlive this; `source`
  /// (the run directory) is named in refusals; `spec` holds the tolerances the maps are drawn
  /// against.
  AdsReportAccumulator(std::string serial,
                       hil::RecordingMeta meta,
                       const ConstantsFile* constants,
                       std::string source,
                       Specification spec);

  /// `line` is the row's ads.csv line (1 = the header), named in refusals.
  void Add(const hil::AdsRecordRow& row, int line);
  const std::string& serial() const { return serial_; }
  /// Every ADS section for the unit.
  std::string Sections() const;

  /// One acquisition's means: references, chamber temperature and compensated values.
  struct Acquisition {
    double alt_ref_ft = 0.0, cas_ref_kt = 0.0, temp_c = 0.0;
    double alt_ft = 0.0, cas_kt = 0.0;
    int n = 0;
  };

 private:
  std::string serial_;
  hil::RecordingMeta meta_;
  const ConstantsFile* constants_;
  Specification spec_;
  std::map<std::tuple<int, int, long, long>, Acquisition> groups_;  // surface-mode rows
  AdsPointSelector raw_points_;                                     // raw-mode rows
  bool raw_rows_ = false;
  std::string raw_refused_;  // why the raw rows give no points, when a row was refused

  std::vector<AdsCalibrationPoint> RawPoints(std::string* why) const;
};

}  // namespace adahrs::calib
