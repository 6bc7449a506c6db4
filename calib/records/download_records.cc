#include "calib/records/download_records.h"

namespace adahrs::calib {

std::optional<int64_t> RecordDownloadAttempt(RecordsStore& store,
                                             const ConstantsRecord& constants,
                                             DownloadRecord attempt) {
  std::optional<int64_t> version =
      store.FindConstantsVersion(constants.serial, constants.file_sha256);
  if (!version && attempt.verified) version = store.AddConstants(constants);
  if (!version) return std::nullopt;
  attempt.constants_version = *version;
  store.AddDownload(attempt);
  return version;
}

}  // namespace adahrs::calib
