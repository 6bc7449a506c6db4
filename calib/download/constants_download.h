// Downloads a constants file into a unit over its maintenance port (docs/download.md):
//   1. IDENTIFY: the unit must be of the file's kind and carry the file's serial (unit_serial.h);
//   2. the unit goes to raw mode, so no packet is compensated with half-written constants;
//   3. the exporter's blocks (constants_blocks.h) are written one by one with WRITE_BLOCK;
//   4. every block is read back with READ_BLOCK and compared bit for bit (readback_check.h);
//   5. only if all are equal: COMMIT, then IDENTIFY must report the committed version and CRC,
//      constants valid;
//   6. the calibrated mode is set: IMU kFullyCalibrated (a file of the staged process: the mode
//      after its last stage, calib/constants/imu_stage.h), ADS kSurface.
// Any failure before COMMIT throws DownloadError and nothing is committed: the unit's flash image
// and constants_version are unchanged (its RAM may hold some new blocks until its next power-on,
// and it is left in raw mode). Every message names the unit role, its port, the constants file
// and the step; instrument failures are quoted (hil::InstrumentError names command and reply).
// Left out: restoring the previous RAM constants after a refusal (a power cycle does that),
// verifying the compensated output (the caller's acceptance run does that).
#pragma once

#include <stdexcept>
#include <string>

#include "calib/constants/constants_file.h"
#include "calib/download/constants_blocks.h"
#include "hil/codecs/unit_protocol_client.h"
#include "hil/drivers/unit_link.h"

namespace adahrs::calib {

class DownloadError : public std::runtime_error {
 public:
  DownloadError(const std::string& message, bool verified)
      : std::runtime_error(message), verified_(verified) {}
  /// Whether every block had been read back equal before the failure.
  bool verified() const { return verified_; }

 private:
  bool verified_;
};

struct DownloadResult {
  hil::IdentifyInfo before{};
  hil::IdentifyInfo after{};
  hil::CommitInfo commit{};
  ConstantsBlocks blocks;
  /// The mode set in step 6: an IMU file of the staged process (ConstantsFile::stages) sets the
  /// mode after its last stage (imu_stage.h), a whole IMU file kFullyCalibrated.
  uint8_t mode = 0;  ///< hil::UnitModeName names it
};

/// Runs steps 1-6 on `link` with `file` (read from `source`). A file of the staged process is
/// written whole like any other (the firmware commits only a complete set, and a fresh unit holds
/// none): its earlier stages as the base held them, its later ones their defaults.
DownloadResult DownloadConstants(hil::UnitLink& link,
                                 const ConstantsFile& file,
                                 const std::string& source);

}  // namespace adahrs::calib
