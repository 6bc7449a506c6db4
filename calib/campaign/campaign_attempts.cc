#include "calib/campaign/campaign_attempts.h"

#include <stdexcept>

#include <fmt/format.h>

#include "calib/acceptance/acceptance_file.h"
#include "calib/records/acceptance_records.h"

namespace adahrs::calib {
namespace {

std::string RoleOf(const std::map<std::string, std::string>& role_of_serial,
                   const std::string& serial) {
  const auto it = role_of_serial.find(serial);
  if (it == role_of_serial.end()) {
    throw std::runtime_error("acceptance judged unit " + serial +
                             ", which no station of the campaign downloaded");
  }
  return it->second;
}

}  // namespace

std::filesystem::path AttemptRunDir(const std::filesystem::path& first_run, int attempt) {
  if (attempt <= 1) return first_run;
  std::filesystem::path dir = first_run;
  dir += fmt::format("-attempt{}", attempt);
  return dir;
}

std::set<std::string> FailedRoles(const AcceptanceRun& judged,
                                  const std::map<std::string, std::string>& role_of_serial) {
  std::set<std::string> roles;
  for (const UnitAcceptance& u : judged.units) {
    if (u.outcome() == Outcome::kFail) roles.insert(RoleOf(role_of_serial, u.serial));
  }
  return roles;
}

hil::Station StationWithRoles(const hil::Station& station, const std::set<std::string>& roles) {
  hil::Station kept = station;
  kept.units.clear();
  for (const hil::UnitEntry& u : station.units) {
    if (roles.count(u.role) != 0) kept.units.push_back(u);
  }
  return kept;
}

std::vector<std::filesystem::path> AcceptanceFilesOf(const AcceptanceRun& judged,
                                                     const Specification& spec,
                                                     const std::string& software_version,
                                                     const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const UnitAcceptance& u : judged.units) {
    files.push_back(dir / u.serial / kAcceptanceFileName);
    if (!std::filesystem::exists(files.back())) {
      return WriteAcceptanceFiles(judged, spec, software_version, dir);
    }
  }
  return files;
}

std::vector<AcceptanceAttemptRecord> AttemptRecords(
    const std::string& campaign_id,
    int attempt,
    const AcceptanceRun& judged,
    const std::vector<std::filesystem::path>& files,
    const std::map<std::string, std::string>& role_of_serial) {
  std::vector<AcceptanceAttemptRecord> records;
  for (size_t i = 0; i < judged.units.size() && i < files.size(); ++i) {
    const UnitAcceptance& u = judged.units[i];
    records.push_back({campaign_id,
                       u.serial,
                       RoleOf(role_of_serial, u.serial),
                       attempt,
                       judged.run_id,
                       AcceptanceRecordsFromFile(files[i]).source_sha256,
                       OutcomeText(u.outcome())});
  }
  return records;
}

}  // namespace adahrs::calib
