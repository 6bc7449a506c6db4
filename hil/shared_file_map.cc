#include "hil/shared_file_map.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>
#include <utility>

namespace adahrs::hil {
namespace {

[[noreturn]] void Throw(int err, const char* what, const std::filesystem::path& path) {
  throw std::system_error(err, std::generic_category(), std::string(what) + " " + path.string());
}

// Maps `bytes` of `fd` (closed here either way); nullptr and errno kept on failure.
char* MapAndClose(int fd, size_t bytes, bool writable) {
  void* map =
      ::mmap(nullptr, bytes, writable ? PROT_READ | PROT_WRITE : PROT_READ, MAP_SHARED, fd, 0);
  const int err = errno;
  ::close(fd);
  errno = err;
  return map == MAP_FAILED ? nullptr : static_cast<char*>(map);
}

}  // namespace

SharedFileMap::~SharedFileMap() {
  if (data_ != nullptr) ::munmap(data_, size_);
}

SharedFileMap::SharedFileMap(SharedFileMap&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)) {}

SharedFileMap& SharedFileMap::operator=(SharedFileMap&& other) noexcept {
  if (this != &other) {
    if (data_ != nullptr) ::munmap(data_, size_);
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
  }
  return *this;
}

SharedFileMap SharedFileMap::Create(const std::filesystem::path& path, size_t bytes) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) Throw(errno, "create", path);
  if (::ftruncate(fd, static_cast<off_t>(bytes)) != 0) {
    const int err = errno;
    ::close(fd);
    Throw(err, "size", path);
  }
  char* data = MapAndClose(fd, bytes, true);
  if (data == nullptr) Throw(errno, "map", path);
  return SharedFileMap(data, bytes);
}

std::optional<SharedFileMap> SharedFileMap::Open(const std::filesystem::path& path, bool writable) {
  const int fd = ::open(path.c_str(), (writable ? O_RDWR : O_RDONLY) | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  const off_t size = ::lseek(fd, 0, SEEK_END);
  if (size <= 0) {
    ::close(fd);
    return SharedFileMap();
  }
  char* data = MapAndClose(fd, static_cast<size_t>(size), writable);
  if (data == nullptr) Throw(errno, "map", path);
  return SharedFileMap(data, static_cast<size_t>(size));
}

}  // namespace adahrs::hil
