#include "common/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace adahrs::common {
namespace {

[[noreturn]] void Fail(const std::filesystem::path& path, const std::string& step, int error) {
  throw AtomicWriteError(path.string() + ": " + step + ": " + std::strerror(error));
}

// Writes all of `text` to `fd`, retrying short writes and interruptions; false with errno set.
bool WriteAll(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n == 0) errno = EIO;  // no progress and no error: do not loop
    if (n <= 0) return false;
    text.remove_prefix(static_cast<size_t>(n));
  }
  return true;
}

// Writes and fsyncs the temporary; on failure removes it and throws naming `path`.
void WriteTemporary(const std::filesystem::path& path,
                    const std::filesystem::path& tmp,
                    std::string_view text) {
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0666);
  if (fd < 0) Fail(path, "cannot create the temporary " + tmp.string(), errno);
  const char* step = nullptr;
  int error = 0;
  if (!WriteAll(fd, text)) {
    step = "write";
    error = errno;
  } else if (::fsync(fd) != 0) {
    step = "fsync";
    error = errno;
  }
  if (::close(fd) != 0 && step == nullptr) {
    step = "close";
    error = errno;
  }
  if (step != nullptr) {
    ::unlink(tmp.c_str());
    Fail(path, std::string("cannot ") + step + " the temporary " + tmp.string(), error);
  }
}

}  // namespace

void WriteFileAtomically(const std::filesystem::path& path, std::string_view text) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  WriteTemporary(path, tmp, text);
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int error = errno;
    ::unlink(tmp.c_str());
    Fail(path, "cannot rename " + tmp.string() + " into place", error);
  }
  // The rename is durable once the directory is: fsync it (a file system that cannot sync a
  // directory, EINVAL, has nothing more to do).
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
  const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd < 0) Fail(path, "cannot open its directory to sync the rename", errno);
  const bool synced = ::fsync(dir_fd) == 0 || errno == EINVAL;
  const int error = errno;
  ::close(dir_fd);
  if (!synced) Fail(path, "cannot fsync its directory after the rename", error);
}

}  // namespace adahrs::common
