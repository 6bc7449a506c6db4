#include "calib/executor/run_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include <fmt/format.h>

#include "calib/executor/executor.h"

namespace adahrs::calib {

RunDirectoryLock::RunDirectoryLock(const std::filesystem::path& run_dir) {
  const std::filesystem::path path = run_dir / kRunLockName;
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw std::runtime_error(
        fmt::format("{}: cannot open: {}", path.string(), std::strerror(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    char holder[32] = {};
    const ssize_t n = ::pread(fd_, holder, sizeof holder - 1, 0);
    ::close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK) {
      throw RunError(
          fmt::format("{} is in use by another adahrs process{}; wait for it to end or stop it",
                      run_dir.string(),
                      n > 0 ? " (pid " + std::string(holder, static_cast<size_t>(n)) + ")" : ""));
    }
    throw std::runtime_error(
        fmt::format("{}: cannot lock: {}", path.string(), std::strerror(error)));
  }
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(fd_, 0) != 0 ||
      ::pwrite(fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
    // The lock holds without the pid; only the refusal message of another process is poorer.
  }
}

RunDirectoryLock::~RunDirectoryLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the last descriptor releases the flock
}

}  // namespace adahrs::calib
