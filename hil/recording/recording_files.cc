#include "hil/recording/recording_files.h"

#include <stdexcept>
#include <string>

namespace adahrs::hil {

std::filesystem::path CsvPathFor(const std::filesystem::path& run_dir,
                                 std::string_view csv_name,
                                 RecordingStorage storage) {
  std::filesystem::path path = run_dir / csv_name;
  if (storage == RecordingStorage::kGzip) path += kGzipSuffix;
  return path;
}

std::filesystem::path StoredCsvPath(const std::filesystem::path& run_dir,
                                    std::string_view csv_name) {
  const std::filesystem::path plain = CsvPathFor(run_dir, csv_name, RecordingStorage::kPlainCsv);
  const std::filesystem::path gzip = CsvPathFor(run_dir, csv_name, RecordingStorage::kGzip);
  const bool has_plain = std::filesystem::exists(plain);
  const bool has_gzip = std::filesystem::exists(gzip);
  if (has_plain && has_gzip) {
    throw std::runtime_error(plain.string() + " and " + gzip.string() +
                             " both exist: a run directory holds one form of each file; remove "
                             "or move the one that is not the run's");
  }
  return has_gzip ? gzip : plain;
}

bool IsCompressed(const std::filesystem::path& path) { return path.extension() == kGzipSuffix; }

}  // namespace adahrs::hil
