// Turns an acceptance.json (calib/acceptance/acceptance_file.h, docs/acceptance.md) into production
// records (records_store.h `acceptance_results`): one record per judged point with its quantity,
// condition ("orientation 11, 62.5 deg/s, 25.0 degC"), error, tolerance, unit and verdict; the
// file's SHA-256 identifies it, so recording the same file twice changes nothing.
// The file is validated by its strict reader first (errors name the file and JSON path).
// Each record carries the point's outcome (PASS, MARGINAL, FAIL) and the SHA-256 of the
// specification file it was judged against. Left out: the worst margins and the specification's
// tables (the file itself keeps them).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "calib/records/records_store.h"

namespace adahrs::calib {

struct AcceptanceRecords {
  std::string source_sha256;  ///< of the acceptance.json bytes
  std::vector<AcceptancePointRecord> points;
};

/// The points of one acceptance.json as records.
AcceptanceRecords AcceptanceRecordsFromFile(const std::filesystem::path& acceptance_json);

}  // namespace adahrs::calib
