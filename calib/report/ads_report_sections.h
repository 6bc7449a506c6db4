// The ADS parts of report.html for one unit: its constants with standard errors, the raw data
// (each bridge's mean code per acquisition against the test set's pressure, one series per chamber
// temperature, and the same less its straight line: the reference method's Figs. 16 and 24), the
// fitted surfaces' residual map (reference altitude or airspeed against chamber temperature, each
// acquisition marked by its |residual| as a fraction of the tolerance there), and the error map
// over altitude x temperature (and airspeed x temperature) against the specification's tolerance
// envelope (calib/acceptance/specification.h). Each point is the mean over one acquisition (rows
// of one step and TAG at one test-set aim); its reference is the test set's reported pressure
// converted by the ISA (pressure altitude, ft) and the calibrated-airspeed formula (kt). The
// compensated value is the unit's own when the row was recorded in surface mode, otherwise the
// double reference compensator with the file's constants at the acquisition's mean raw codes,
// with the surfaces' hysteresis states as the fit models them (the unit's operators,
// calib/ads_calibration/unit_hysteresis_operator.h, driven by the test set's pressure and the
// chamber temperature from acquisition to acquisition in step order; no states without
// hysteresis terms); the figure says which. Rows in rejected intervals and rows with TAG 0
// (between acquisitions) are left out.
#pragma once

#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/constants/constants_file.h"
#include "hil/recording/recording_format.h"
#include "hil/recording/recording_meta.h"

namespace adahrs::calib {

/// The acquisitions of one unit, summed one row at a time: Add every ads.csv row in file order
/// (other units' rows are passed over), then Sections(). Holds one sum per acquisition.
class AdsReportAccumulator {
 public:
  /// `meta` supplies rejected intervals; `constants` may be null and must outlive this.
  AdsReportAccumulator(std::string serial, hil::RecordingMeta meta, const ConstantsFile* constants);

  void Add(const hil::AdsRecordRow& row);
  const std::string& serial() const { return serial_; }
  /// Every ADS section for the unit.
  std::string Sections() const;

  /// Sums over one acquisition's rows (means once divided): raw codes and reference pressures of
  /// every row recorded in raw mode (n_raw), compensated values and references of every row that
  /// has them (n); a raw acquisition's compensated values are computed from its means.
  struct Acquisition {
    double alt_ref_ft = 0.0, cas_ref_kt = 0.0, temp_c = 0.0;
    double alt_ft = 0.0, cas_kt = 0.0;
    int n = 0;
    double ps_ref_pa = 0.0, qc_ref_pa = 0.0, ps_cnt = 0.0, pt_cnt = 0.0, ps_bridge_cnt = 0.0,
           pt_bridge_cnt = 0.0, raw_temp_c = 0.0;
    int n_raw = 0;
  };

 private:
  std::string serial_;
  hil::RecordingMeta meta_;
  const ConstantsFile* constants_;
  std::map<std::tuple<int, int, long, long>, Acquisition> groups_;
  bool unit_values_ = false;
};

/// Every ADS section for `serial`; `constants` may be null. `meta` supplies rejected intervals.
std::string AdsReportSections(const std::string& serial,
                              const std::vector<hil::AdsRecordRow>& rows,
                              const hil::RecordingMeta& meta,
                              const ConstantsFile* constants);

}  // namespace adahrs::calib
