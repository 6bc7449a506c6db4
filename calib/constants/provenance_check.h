// Whether the recordings a constants file was fitted on are still what the fit read: each
// recording of the provenance is checksummed again (recording_checksum.h) where its path leads on
// this machine. A changed recording means the constants no longer stand on the data on record;
// one that cannot be read here (another machine, moved) is reported as such, not as a change.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "calib/constants/constants_file.h"

namespace adahrs::calib {

struct RecordingCheck {
  std::string path;
  std::string recorded_sha256;
  std::optional<std::string> current_sha256;  ///< nullopt: not readable here
  std::string why_unreadable;
  bool changed() const { return current_sha256 && *current_sha256 != recorded_sha256; }
  std::string Describe()
      const;  ///< "PATH: unchanged" / "PATH: changed since the fit (a -> b)" / ...
};

/// Checks every recording of `provenance`, in its order.
std::vector<RecordingCheck> CheckRecordings(const ConstantsProvenance& provenance);

/// Throws std::runtime_error naming `constants_path`, the recording and both checksums when one of
/// the recordings changed since the fit; returns the checks (unreadable ones for a note).
std::vector<RecordingCheck> RequireUnchangedRecordings(const ConstantsFile& file,
                                                       const std::string& constants_path);

}  // namespace adahrs::calib
