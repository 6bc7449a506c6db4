// The ADS parts of report.html for one unit: its constants with standard errors, and the error map
// over altitude x temperature (and airspeed x temperature) against the specification's tolerance
// envelope (calib/acceptance/specification.h). Each point is the mean over one acquisition (rows
// of one step and TAG at one test-set aim); its reference is the test set's reported pressure
// converted by the ISA (pressure altitude, ft) and the calibrated-airspeed formula (kt). The
// compensated value is the unit's own when the row was recorded in surface mode, otherwise the
// double reference compensator with the file's constants on the recorded raw codes; the figure
// says which. Rows in rejected intervals and rows with TAG 0 (between acquisitions) are left out.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calib/constants/constants_file.h"
#include "hil/recording/recording_format.h"

namespace adahrs::calib {

/// Every ADS section for `serial`; `constants` may be null. `meta` supplies rejected intervals.
std::string AdsReportSections(const std::string& serial,
                              const std::vector<hil::AdsRecordRow>& rows,
                              const nlohmann::json& meta,
                              const ConstantsFile* constants);

}  // namespace adahrs::calib
