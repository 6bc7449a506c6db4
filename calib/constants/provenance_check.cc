#include "calib/constants/provenance_check.h"

#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "calib/constants/recording_checksum.h"

namespace adahrs::calib {

std::string RecordingCheck::Describe() const {
  if (!current_sha256) return fmt::format("{}: not checked, {}", path, why_unreadable);
  if (changed()) {
    return fmt::format("{}: CHANGED since the fit (sha256 {} then, {} now)",
                       path,
                       recorded_sha256,
                       *current_sha256);
  }
  return fmt::format("{}: unchanged since the fit", path);
}

std::vector<RecordingCheck> CheckRecordings(const ConstantsProvenance& provenance) {
  std::vector<RecordingCheck> checks;
  for (const RecordingReference& r : provenance.recordings) {
    RecordingCheck c{r.path, r.sha256, std::nullopt, ""};
    std::error_code ec;
    if (!std::filesystem::is_directory(r.path, ec)) {
      c.why_unreadable = "no such run directory here";
    } else {
      try {
        c.current_sha256 = RecordingSha256(r.path);
      } catch (const std::exception& e) {
        c.why_unreadable = e.what();
      }
    }
    checks.push_back(std::move(c));
  }
  return checks;
}

std::vector<RecordingCheck> RequireUnchangedRecordings(const ConstantsFile& file,
                                                       const std::string& constants_path) {
  std::vector<RecordingCheck> checks = CheckRecordings(file.provenance);
  for (const RecordingCheck& c : checks) {
    if (c.changed()) {
      throw std::runtime_error(
          fmt::format("{}: the constants of {} were fitted on a recording that changed since: {}; "
                      "fit again",
                      constants_path,
                      file.serial,
                      c.Describe()));
    }
  }
  return checks;
}

}  // namespace adahrs::calib
