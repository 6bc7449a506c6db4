// The constants of a constants.json as a report table: every number with its 1-sigma standard
// error, by JSON path (the names of calibration_constants.h: thermal[i].k[j] in the channel's U
// units per count^j, accel[i].offset_duty, scale_duty_per_g, gyro[i].l[j] deg/s per count^j,
// ca_mps2_per_g, cg, surfaces' coefficients), plus the file's strategy and provenance.
#pragma once

#include <string>

#include "calib/constants/constants_file.h"
#include "calib/report/html_builder.h"

namespace adahrs::calib {

/// Rows: name (constant_names.h), JSON path, value, standard error ("not estimated" for null).
HtmlTable ConstantsTable(const ConstantsFile& file);

/// The strategy / created / software / provenance lines and the table.
std::string ConstantsSection(const ConstantsFile& file);

}  // namespace adahrs::calib
