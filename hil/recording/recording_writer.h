// Writes a run directory in the recording format (recording_format.h). Rows are appended to the
// CSVs as they arrive, stored gzip-compressed (imu.csv.gz, ads.csv.gz) or plain (recording_files.h;
// csv_file_writer.h says how a compressed file stays readable after a crash). Flush(durable=true)
// hands every row to the kernel (ending the gzip members) and fsyncs both files, which the
// executor does at every step boundary so that a crash loses nothing that was logged before it.
// Each row's frame index (the frame and t_sample_s columns) is the row's own when it carries one,
// else counted per unit from seq and t_s, or from a lockstep rig's packet index when the row
// carries one (frame_count.h), continuing an existing file's count.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "hil/recording/csv_file_writer.h"
#include "hil/recording/frame_count.h"
#include "hil/recording/recording_files.h"
#include "hil/recording/recording_format.h"
#include "hil/recording/recording_meta.h"
#include "hil/recording/row_text.h"

namespace adahrs::hil {

class RecordingWriter {
 public:
  /// Creates `run_dir` (and parents) and opens its imu and ads CSVs for appending, writing the
  /// header line into each new file. The files are stored as `storage` says unless `run_dir`
  /// holds them already (a resumed run): then they keep the form they have. Throws
  /// std::runtime_error naming the path on failure, on an existing file whose header is not this
  /// version's, and when both forms of a file exist.
  explicit RecordingWriter(const std::filesystem::path& run_dir,
                           RecordingStorage storage = RecordingStorage::kGzip,
                           int gzip_level = CsvFileWriter::kGzipLevel);
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  /// Writes meta.json atomically (temporary file + rename); `meta` gets format_version added.
  void WriteMeta(RecordingMeta meta) const;
  /// meta.json given as JSON (tests, tools): read as RecordingMeta first, so it is refused as a
  /// reader would refuse it, then written as WriteMeta writes it.
  void WriteMetaJson(nlohmann::json meta) const;
  void Append(const ImuRecordRow& row);
  void Append(const AdsRecordRow& row);
  /// Hands every appended row to the kernel; with `durable`, also fsyncs the files.
  void Flush(bool durable);
  /// Hands rows to the kernel in pieces a crash leaves readable (CsvFileWriter::FlushIfDue):
  /// all of them for plain files, whole gzip members of compressed ones.
  void FlushIfDue();
  /// Fsyncs what was handed to the kernel before, without touching the buffers: safe to call
  /// while another thread appends (under its own lock), so a slow disk does not hold it up.
  void SyncFlushed() const;

  const std::filesystem::path& run_dir() const { return run_dir_; }
  const std::filesystem::path& imu_path() const { return imu_->path(); }
  const std::filesystem::path& ads_path() const { return ads_->path(); }
  uint64_t imu_rows() const { return imu_rows_; }
  uint64_t ads_rows() const { return ads_rows_; }

 private:
  std::filesystem::path run_dir_;
  std::unique_ptr<CsvFileWriter> imu_;
  std::unique_ptr<CsvFileWriter> ads_;
  uint64_t imu_rows_ = 0;
  uint64_t ads_rows_ = 0;
  std::vector<char> row_buffer_;  ///< the row being formatted (RowText), reused
  // Per unit serial, its frame count (units of both files: serials do not repeat across kinds).
  std::map<std::string, FrameCounter, std::less<>> frames_;
  int64_t Frame(
      const std::string& unit, uint32_t seq, double t_s, int64_t frame, int64_t packet_index);
};

}  // namespace adahrs::hil
