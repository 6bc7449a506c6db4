// Writes a run directory in the recording format (recording_format.h). Rows are appended to the
// CSVs as they arrive; Flush(durable=true) flushes and fsyncs both files, which the executor does
// at every step boundary so that a crash loses nothing that was logged before it.
#pragma once

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "hil/recording/recording_format.h"
#include "hil/recording/row_text.h"

namespace adahrs::hil {

class RecordingWriter {
 public:
  /// Creates `run_dir` (and parents) and opens imu.csv and ads.csv for appending, writing the
  /// header line into each new file. Throws std::runtime_error naming the path on failure.
  explicit RecordingWriter(const std::filesystem::path& run_dir);
  ~RecordingWriter();
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  /// Writes meta.json atomically (temporary file + rename); `meta` gets format_version added.
  void WriteMeta(nlohmann::json meta) const;
  void Append(const ImuRecordRow& row);
  void Append(const AdsRecordRow& row);
  /// Flushes buffered rows; with `durable`, also fsyncs the files.
  void Flush(bool durable);
  /// Fsyncs what was flushed before, without touching the stdio buffers: safe to call while
  /// another thread appends (under its own lock), so a slow disk does not hold the writers up.
  void SyncFlushed() const;

  const std::filesystem::path& run_dir() const { return run_dir_; }
  uint64_t imu_rows() const { return imu_rows_; }
  uint64_t ads_rows() const { return ads_rows_; }

 private:
  std::filesystem::path run_dir_;
  // 1 MiB stdio buffers: a fast rig's rows at the default 4 KiB cost a write() per ~20 rows.
  std::unique_ptr<char[]> imu_buffer_;
  std::unique_ptr<char[]> ads_buffer_;
  void Write(std::FILE* file, const RowText& row, std::string_view name);

  std::FILE* imu_ = nullptr;
  std::FILE* ads_ = nullptr;
  uint64_t imu_rows_ = 0;
  uint64_t ads_rows_ = 0;
  std::vector<char> row_buffer_;  ///< the row being formatted (RowText), reused
};

}  // namespace adahrs::hil
