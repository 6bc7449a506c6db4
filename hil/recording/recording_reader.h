// Reads a run directory in the recording format (docs/recording-format.md) back into rows, as the
// solvers and reports consume it. Refuses what it cannot trust and says exactly where: a missing
// or unreadable file, a format version it does not know, a header that lacks one of the contract's
// columns or repeats a name, a row with another number of columns than its header, a cell that is
// not a number of its column's type or is out of its type's range — each error names the file, the
// 1-based line and the column name. Per unit, rows must come in arrival order: a row of a unit
// meta.json does not list, a negative step, a unit's time going back or its previous row repeated
// is refused by file and line. A truncated last line (a crash while writing) is reported as such,
// not silently dropped: `ReadOptions::allow_truncated_tail` accepts it and counts it, as a resumed
// run needs. Reads format versions 1 to 4 (recording_format.h), each CSV plain or gzip-compressed
// (recording_files.h); the ADS raw-count columns are found by the name the file's version gives
// them (ps_counts … in versions 1 to 3, ps_cnt … in 4); version 1 rows have no compensated
// values; rows of versions 1 and 2 get their frame counted from seq and t_s (frame_count.h), rows
// of versions 3 and 4 carry it and it must not go back. Columns are found by name, in any order;
// a column the contract does not know is ignored and named in `Recording::notes` (a foreign
// logger's extra channels lose nothing that is read).
// From version 2 the compensated cells are all empty exactly when the row's mode is 0 (raw).
// meta.json's optional "rejected_intervals" (rows that are NOT calibration data) are parsed
// strictly too; the rest of meta.json is handed over as JSON.
#pragma once

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hil/recording/recording_error.h"
#include "hil/recording/recording_format.h"
#include "hil/recording/recording_meta.h"

namespace adahrs::hil {

struct ReadOptions {
  bool allow_truncated_tail = false;
};

struct Recording {
  RecordingMeta meta;
  std::vector<ImuRecordRow> imu;
  std::vector<AdsRecordRow> ads;
  int truncated_lines = 0;  ///< incomplete last lines skipped (only with allow_truncated_tail)
  /// What the reader passed over without refusing: columns the format does not know, named with
  /// their file and position.
  std::vector<std::string> notes;
};

/// Reads meta.json, imu.csv and ads.csv of `run_dir`.
Recording ReadRecording(const std::filesystem::path& run_dir, const ReadOptions& options = {});

/// meta.json of `run_dir`, checked as ReadRecording checks it, without reading the rows.
Recording ReadRecordingMeta(const std::filesystem::path& run_dir);

/// Where StreamRecording hands each row, in file order, with its 1-based CSV line. A sink may be
/// empty: that file's rows are still read and checked, then dropped.
struct RowSinks {
  std::function<void(ImuRecordRow&&, int line)> imu;
  std::function<void(AdsRecordRow&&, int line)> ads;
};

/// ReadRecording without holding the rows: each is checked as ReadRecording checks it and handed
/// to `sinks`; the result carries meta.json, the rejected intervals and the truncation count, and
/// empty row vectors. For recordings too large to hold twice (ten million rows of imu.csv).
Recording StreamRecording(const std::filesystem::path& run_dir,
                          const RowSinks& sinks,
                          const ReadOptions& options = {});

/// True when `t_s` lies inside one of the recording's rejected intervals (its rows there are not
/// calibration data).
bool IsRejected(const Recording& recording, double t_s);

}  // namespace adahrs::hil
