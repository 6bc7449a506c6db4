#include "calib/records/acceptance_records.h"

#include "calib/acceptance/acceptance_file.h"
#include "calib/records/records_sources.h"
#include "common/sha256.h"

namespace adahrs::calib {

AcceptanceRecords AcceptanceRecordsFromFile(const std::filesystem::path& acceptance_json) {
  const AcceptanceFile file = ReadAcceptanceFile(acceptance_json);
  AcceptanceRecords records;
  records.source_sha256 = common::FileSha256(acceptance_json);
  for (const AcceptancePoint& p : file.unit.points) {
    records.points.push_back({file.unit.serial,
                              file.run.run_id,
                              p.quantity,
                              "step " + std::to_string(p.step) + ", " + p.Condition(),
                              p.error,
                              p.tolerance,
                              p.unit,
                              p.pass,
                              OutcomeText(p.outcome()),
                              file.specification_id.sha256});
  }
  return records;
}

}  // namespace adahrs::calib
