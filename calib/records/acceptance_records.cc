#include "calib/records/acceptance_records.h"

#include "calib/acceptance/acceptance_file.h"
#include "calib/records/records_sources.h"

namespace adahrs::calib {

AcceptanceRecords AcceptanceRecordsFromFile(const std::filesystem::path& acceptance_json) {
  const nlohmann::json file = ReadAcceptanceFile(acceptance_json);
  AcceptanceRecords records;
  records.source_sha256 = FileSha256(acceptance_json);
  const std::string serial = file["serial"].get<std::string>();
  const std::string run_id = file["run"]["run_id"].get<std::string>();
  for (const nlohmann::json& p : file["points"]) {
    records.points.push_back(
        {serial,
         run_id,
         p["quantity"].get<std::string>(),
         "step " + std::to_string(p["step"].get<int>()) + ", " + p["condition"].get<std::string>(),
         p["error"].get<double>(),
         p["tolerance"].get<double>(),
         p["unit"].get<std::string>(),
         p["pass"].get<bool>()});
  }
  return records;
}

}  // namespace adahrs::calib
