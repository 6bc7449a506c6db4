// The checksum that ties constants (constants.json provenance) to the recording they came from:
// SHA-256 over the bytes of meta.json, imu.csv and ads.csv of a run directory as they are stored
// (imu.csv.gz and ads.csv.gz when compressed: the compressed bytes), concatenated in that order
// (docs/constants-file.md), computed with OpenSSL's libcrypto. Equal to
// `cat meta.json imu.csv ads.csv | sha256sum` (or `... imu.csv.gz ads.csv.gz ...`).
// Not covered: truth/ (simulation only, never an input of calibration), any other file in the run
// directory. meta.json is rewritten while a run is in progress, so a running recording's checksum
// changes; checksum a finished run. A process keeps each run's checksum with the files' device,
// inode, size and modification time, and reads the files again when any of them changed (files
// modified within the last 2 s are always read: the kernel's time stamps are coarser than writes).
#pragma once

#include <filesystem>
#include <string>

namespace adahrs::calib {

/// 64 lowercase hex digits; throws std::runtime_error naming the file that cannot be read.
std::string RecordingSha256(const std::filesystem::path& run_dir);

}  // namespace adahrs::calib
