#include "hil/recording/torn_tail.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

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

}  // namespace

std::optional<std::filesystem::path> SetAsideTornTail(const std::filesystem::path& csv_path) {
  if (!std::filesystem::exists(csv_path)) return std::nullopt;
  std::string text;
  {
    std::ifstream in(csv_path, std::ios::binary);
    if (!in) Fail(csv_path, "cannot open for reading");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    text = buffer.str();
  }
  if (text.empty() || text.back() == '\n') return std::nullopt;
  const size_t last_newline = text.rfind('\n');
  const size_t keep = last_newline == std::string::npos ? 0 : last_newline + 1;
  std::filesystem::path torn;
  for (int n = 1;; ++n) {
    torn = csv_path;
    torn += ".torn-" + std::to_string(n);
    if (!std::filesystem::exists(torn)) break;
  }
  WriteDurably(torn, text.substr(keep));
  if (::truncate(csv_path.c_str(), static_cast<off_t>(keep)) != 0)
    Fail(csv_path, "truncate failed");
  return torn;
}

}  // namespace adahrs::hil
