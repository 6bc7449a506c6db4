// A constants file (constants_file.h) as the fixed-point blocks the unit stores
// (firmware_model/target/imu_constants.h: 0x01..0x0F; ads_constants.h: 0x21, 0x22), produced by
// the firmware exporter (constants_exporter.h) and serialised by the target's own block reader,
// so the words are exactly those a unit holding these constants would read back. The exporter's
// worst-case quantisation error per output quantity comes with them.
// Refusal: ConstantsBlocksError naming the constants file when the exporter cannot represent a
// constant (its reason quoted) or the file holds no constants of its kind.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "calib/constants/constants_file.h"
#include "firmware_model/constants_exporter.h"

namespace adahrs::calib {

class ConstantsBlocksError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ConstantsBlock {
  uint8_t block_id = 0;
  std::string name;  ///< "thermal az1", "accel offsets and scales", "gyro x cubic", "CA", ...
  std::vector<int16_t> words;
};

/// One exporter error bound, in the output quantity's unit.
struct ExportErrorBound {
  std::string
      quantity;  ///< "accel_g", "rate_dps", "accel_mps2", "rate_full_dps", "altitude_ft", ...
  double bound = 0.0;
};

struct ConstantsBlocks {
  hil::UnitKind kind = hil::UnitKind::kImu;
  std::vector<ConstantsBlock> blocks;  ///< in block id order, the order they are written
  std::vector<ExportErrorBound> error_bounds;
  firmware_model::ImuExportReport imu_report;  ///< meaningful for IMU files
  firmware_model::AdsExportReport ads_report;  ///< meaningful for ADS files
};

/// Exports `file` (read from `source`, for messages).
ConstantsBlocks ExportConstantsBlocks(const ConstantsFile& file, const std::string& source);

}  // namespace adahrs::calib
