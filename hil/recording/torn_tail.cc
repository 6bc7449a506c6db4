#include "hil/recording/torn_tail.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "hil/recording/gzip_reader.h"
#include "hil/recording/recording_files.h"

namespace adahrs::hil {
namespace {

[[noreturn]] void Fail(const std::filesystem::path& path, const char* what) {
  throw std::runtime_error(path.string() + ": " + what + ": " + std::strerror(errno));
}

void WriteDurably(const std::filesystem::path& path, const std::string& bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) Fail(path, "cannot create");
  const bool ok = ::write(fd, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size()) &&
                  ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) Fail(path, "write failed");
}

// The bytes [offset, offset + size) of `path`.
std::string ReadRange(const std::filesystem::path& path, uint64_t offset, uint64_t size) {
  std::ifstream in(path, std::ios::binary);
  if (!in) Fail(path, "cannot open for reading");
  std::string bytes(size, '\0');
  in.seekg(static_cast<std::streamoff>(offset));
  if (!in.read(bytes.data(), static_cast<std::streamsize>(size))) Fail(path, "read failed");
  return bytes;
}

// Bytes of `path` (`size` long) that end cleanly: up to its last newline when plain (read
// backwards from the end), up to its last complete gzip member when compressed.
uint64_t CleanEnd(const std::filesystem::path& path, uint64_t size) {
  if (IsCompressed(path)) {
    GzipReader gzip(path);
    std::vector<char> sink(size_t{1} << 20);
    while (gzip.Read(sink.data(), sink.size()) > 0) {
    }
    return gzip.truncated() ? gzip.complete_bytes() : size;
  }
  constexpr uint64_t kBlockBytes = uint64_t{1} << 16;
  for (uint64_t end = size; end > 0;) {
    const uint64_t begin = end > kBlockBytes ? end - kBlockBytes : 0;
    const std::string block = ReadRange(path, begin, end - begin);
    const size_t newline = block.rfind('\n');
    if (newline != std::string::npos) return begin + newline + 1;
    end = begin;
  }
  return 0;
}

}  // namespace

std::optional<std::filesystem::path> SetAsideTornTail(const std::filesystem::path& csv_path) {
  if (!std::filesystem::exists(csv_path)) return std::nullopt;
  const uint64_t size = std::filesystem::file_size(csv_path);
  const uint64_t keep = CleanEnd(csv_path, size);
  if (keep == size) return std::nullopt;
  std::filesystem::path torn;
  for (int n = 1;; ++n) {
    torn = csv_path;
    torn += ".torn-" + std::to_string(n);
    if (!std::filesystem::exists(torn)) break;
  }
  WriteDurably(torn, ReadRange(csv_path, keep, size - keep));
  if (::truncate(csv_path.c_str(), static_cast<off_t>(keep)) != 0)
    Fail(csv_path, "truncate failed");
  return torn;
}

}  // namespace adahrs::hil
