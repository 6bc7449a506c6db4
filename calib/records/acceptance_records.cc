#include "calib/records/acceptance_records.h"

#include "calib/acceptance/acceptance_file.h"
#include "calib/records/records_sources.h"

namespace adahrs::calib {

AcceptanceRecords AcceptanceRecordsFromFile(const std::filesystem::path& acceptance_json) {
  const AcceptanceFile file = ReadAcceptanceFile(acceptance_json);
  AcceptanceRecords records;
  records.source_sha256 = FileSha256(acceptance_json);
  for (const AcceptanceFilePoint& read : file.points) {
    const AcceptancePoint& p = read.point;
    records.points.push_back({file.serial,
                              file.run.run_id,
                              p.quantity,
                              "step " + std::to_string(p.step) + ", " + read.condition,
                              p.error,
                              p.tolerance,
                              p.unit,
                              p.pass});
  }
  return records;
}

}  // namespace adahrs::calib
