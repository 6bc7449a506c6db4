// The checks on an external strategy's reply (docs/strategies-external.md "The checks"): one JSON
// object of the protocol and version, for the unit asked, whose constants and standard errors read
// as a constants file's would and fit the firmware format asked: format 3's terms present exactly
// when asked, every number representable in the firmware's blocks, each channel's thermometer the
// channel table's. Messages carry the reply's JSON path.
// Left out: judging the constants' quality (acceptance does that on the units).
#pragma once

#include <string>
#include <vector>

#include "calib/constants/constants_file.h"

namespace adahrs::calib {

struct CheckedReply {
  firmware_model::ImuCalibrationConstants constants;
  nlohmann::json standard_errors;  ///< the constants file's shape; null where not estimated
  std::vector<std::string> log;
};

/// Checks `reply_bytes` for unit `serial`; throws std::runtime_error with the cause and the JSON
/// path (the caller adds the program's name and stderr).
CheckedReply CheckExternalReply(const std::string& reply_bytes,
                                const std::string& serial,
                                int firmware_format);

}  // namespace adahrs::calib
