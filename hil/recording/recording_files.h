// Where a run directory keeps its rows: each CSV of the recording format (imu.csv, ads.csv) is
// stored either as plain text or gzip-compressed under the same name with `.gz` added
// (docs/recording-format.md). A run directory holds one form of each file, never both.
#pragma once

#include <filesystem>
#include <string_view>

namespace adahrs::hil {

/// How a writer stores a recording's CSVs.
enum class RecordingStorage {
  kGzip,      ///< imu.csv.gz, ads.csv.gz: one gzip member per flush (the default)
  kPlainCsv,  ///< imu.csv, ads.csv
};

inline constexpr std::string_view kGzipSuffix = ".gz";

/// The path of `csv_name` ("imu.csv") as `storage` stores it.
std::filesystem::path CsvPathFor(const std::filesystem::path& run_dir,
                                 std::string_view csv_name,
                                 RecordingStorage storage);

/// The stored file of `csv_name` in `run_dir`: the plain or the compressed one, whichever exists
/// (the plain path when neither does). Throws std::runtime_error naming both when both exist.
std::filesystem::path StoredCsvPath(const std::filesystem::path& run_dir,
                                    std::string_view csv_name);

/// True when `path` is a compressed CSV (its name ends in `.gz`).
bool IsCompressed(const std::filesystem::path& path);

}  // namespace adahrs::hil
