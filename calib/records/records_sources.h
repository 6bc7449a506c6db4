// Turns the pipeline's files into production records (records_store.h): a run directory
// (meta.json of recording format 2, docs/recording-format.md; checksum recording_checksum.h) and a
// constants.json (constants_file.h, docs/constants-file.md). The files are validated by their own
// strict readers first, so nothing malformed reaches the database; errors name the file and JSON
// path. Left out: acceptance files (acceptance_records.h reads those).
#pragma once

#include <filesystem>
#include <string>

#include "calib/records/records_store.h"

namespace adahrs::calib {

struct RunRecordOptions {
  /// Record a run whose recording has sample time defects (hil/recording/sample_time_check.h)
  /// instead of refusing it.
  bool accept_sample_time_defects = false;
};

/// The run, its units and its steps (with each step's rejected time) from `run_dir`, after every
/// row of its recording was read and checked (refused by file and line: a bad cell, a unit not in
/// meta.json, a unit's time going backwards, a repeated row, and unless `options` accept them,
/// rows whose sample time left the bound of their line's buffering).
RunRecord RunRecordFromDirectory(const std::filesystem::path& run_dir,
                                 const RunRecordOptions& options = {});

/// The constants file as the next version of its unit; the file checksum is SHA-256 of its bytes.
/// Refused (std::runtime_error naming the file and the recording) when a recording it was fitted
/// on changed since the fit (provenance_check.h).
ConstantsRecord ConstantsRecordFromFile(const std::filesystem::path& constants_json);

}  // namespace adahrs::calib
