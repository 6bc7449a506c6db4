// Reads a run directory in the recording format (docs/recording-format.md) back into rows, as the
// solvers and reports consume it. Refuses what it cannot trust and says exactly where: a missing
// or unreadable file, a format version it does not know, a header that is not the contract's, a row
// with the wrong number of columns, a cell that is not a number of its column's type or is out of
// its type's range — each error names the file, the 1-based line and the column name.
// A truncated last line (a crash while writing) is reported as such, not silently dropped:
// `ReadOptions::allow_truncated_tail` accepts it and counts it, as a resumed run needs.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hil/recording/recording_format.h"

namespace adahrs::hil {

class RecordingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ReadOptions {
  bool allow_truncated_tail = false;
};

struct Recording {
  nlohmann::json meta;
  std::vector<ImuRecordRow> imu;
  std::vector<AdsRecordRow> ads;
  int truncated_lines = 0;  ///< incomplete last lines skipped (only with allow_truncated_tail)
};

/// Reads meta.json, imu.csv and ads.csv of `run_dir`.
Recording ReadRecording(const std::filesystem::path& run_dir, const ReadOptions& options = {});

}  // namespace adahrs::hil
