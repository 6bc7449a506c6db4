// What a download attempt leaves in the records (docs/records.md). A constants file becomes a
// version of its unit only when a unit accepted it (every block read back equal); a refused
// attempt is recorded against the version the same file already is, and not at all when it is
// none, so a refused file, or another unit's, never becomes a permanent constants version.
#pragma once

#include <optional>

#include "calib/records/records_store.h"

namespace adahrs::calib {

/// Records `attempt` (its `verified` says whether the unit accepted the blocks) for the file
/// `constants`; returns the version it was recorded against, or nullopt when nothing was recorded.
std::optional<int64_t> RecordDownloadAttempt(RecordsStore& store,
                                             const ConstantsRecord& constants,
                                             DownloadRecord attempt);

}  // namespace adahrs::calib
