// Reads a run directory in the recording format (docs/recording-format.md) back into rows, as the
// solvers and reports consume it. Refuses what it cannot trust and says exactly where: each error
// names the file, the 1-based line and the column name. Per unit, rows must come in arrival order.
// A truncated last line (a crash while writing) is reported, not silently dropped;
// `ReadOptions::allow_truncated_tail` accepts it and counts it, as a resumed run needs. Reads
// format versions 1 to 4 (recording_format.h), each CSV plain or gzip-compressed
// (recording_files.h), columns found by name in any order; a column the contract does not know is
// ignored and named in `Recording::notes`. Rows of versions 1 and 2 get their frame counted from
// seq and t_s (frame_count.h). meta.json's optional "rejected_intervals" are parsed strictly too.
// Units: as the format's columns (t_s and t_sample_s in seconds, raw counts, compensated values).
// Every refusal: docs/recording-format.md ("Errors"); frames: "Sample time".
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
#include "hil/recording/sample_time_check.h"

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
  /// Units whose rows' sample times left their line's bound (sample_time_check.h), by file; a
  /// recording defect the reader reports and `records add-run` refuses.
  std::vector<SampleTimeDefect> sample_time_defects;
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
