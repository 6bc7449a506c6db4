#include "rig_sim/pty_clients.h"

#include <dirent.h>
#include <unistd.h>

#include <cctype>
#include <climits>
#include <cstdlib>
#include <string>

namespace adahrs::rig_sim {
namespace {

bool AllDigits(const char* name) {
  if (*name == '\0') return false;
  for (const char* c = name; *c != '\0'; ++c) {
    if (std::isdigit(static_cast<unsigned char>(*c)) == 0) return false;
  }
  return true;
}

// Descriptors of one process's fd directory that resolve to `device_path`, `skip_fd` excepted.
int CountIn(const std::string& fd_dir, const std::string& device_path, long skip_fd) {
  DIR* dir = ::opendir(fd_dir.c_str());
  if (dir == nullptr) return 0;  // gone meanwhile, or another user's
  int count = 0;
  char target[PATH_MAX];
  while (const dirent* entry = ::readdir(dir)) {
    if (!AllDigits(entry->d_name)) continue;
    if (std::strtol(entry->d_name, nullptr, 10) == skip_fd) continue;
    const std::string link = fd_dir + "/" + entry->d_name;
    const ssize_t n = ::readlink(link.c_str(), target, sizeof target - 1);
    if (n <= 0) continue;
    target[n] = '\0';
    if (device_path == target) ++count;
  }
  ::closedir(dir);
  return count;
}

}  // namespace

std::optional<int> CountPtyClients(const std::string& device_path, int own_fd) {
  DIR* proc = ::opendir("/proc");
  if (proc == nullptr) return std::nullopt;
  const long self = static_cast<long>(::getpid());
  int count = 0;
  while (const dirent* entry = ::readdir(proc)) {
    if (!AllDigits(entry->d_name)) continue;
    const long pid = std::strtol(entry->d_name, nullptr, 10);
    count += CountIn(
        std::string("/proc/") + entry->d_name + "/fd", device_path, pid == self ? own_fd : -1);
  }
  ::closedir(proc);
  return count;
}

}  // namespace adahrs::rig_sim
