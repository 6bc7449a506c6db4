// One adahrs process per run directory: an exclusive flock on <run_dir>/run.lock, held for the
// life of the object. The kernel drops it when the process ends, however it ends, so a crashed
// run never leaves its directory locked; a second `run --resume` on a live run is refused instead
// of opening the live run's ports under it. The file holds the holder's pid, for the message.
#pragma once

#include <filesystem>

namespace adahrs::calib {

inline constexpr const char* kRunLockName = "run.lock";

class RunDirectoryLock {
 public:
  /// Throws RunError naming the directory (and the holder's pid) when another process holds it,
  /// std::runtime_error when the lock file cannot be opened.
  explicit RunDirectoryLock(const std::filesystem::path& run_dir);
  ~RunDirectoryLock();
  RunDirectoryLock(const RunDirectoryLock&) = delete;
  RunDirectoryLock& operator=(const RunDirectoryLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace adahrs::calib
