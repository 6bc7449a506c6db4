#include "calib/constants/recording_checksum.h"

#include <sys/stat.h>

#include <array>
#include <ctime>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <vector>

#include "common/sha256.h"
#include "hil/recording/recording_files.h"
#include "hil/recording/recording_format.h"

namespace adahrs::calib {
namespace {

// What identifies a file's present content without reading it: device, inode, size and
// modification time (ns). A file rewritten in place changes its time; meta.json is replaced by a
// rename, which changes its inode. The kernel stamps times at its tick, so two writes within one
// tick can share a time: a checksum is kept only for files last modified over kSettled_s ago.
using FileStamp = std::array<int64_t, 5>;
constexpr int64_t kSettled_s = 2;

std::optional<FileStamp> Stamp(const std::filesystem::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;
  return FileStamp{static_cast<int64_t>(st.st_dev),
                   static_cast<int64_t>(st.st_ino),
                   static_cast<int64_t>(st.st_size),
                   static_cast<int64_t>(st.st_mtim.tv_sec),
                   static_cast<int64_t>(st.st_mtim.tv_nsec)};
}

std::string Sha256OfFiles(const std::vector<std::filesystem::path>& files);

}  // namespace

std::string RecordingSha256(const std::filesystem::path& run_dir) {
  // One process checks the same recordings again and again (every constants file's provenance,
  // the records): the checksum is kept with the files' stamps and computed again when one changed.
  static std::mutex mutex;
  static std::map<std::string, std::pair<std::vector<FileStamp>, std::string>> known;
  const std::vector<std::filesystem::path> files = {run_dir / hil::kMetaJsonName,
                                                    hil::StoredCsvPath(run_dir, hil::kImuCsvName),
                                                    hil::StoredCsvPath(run_dir, hil::kAdsCsvName)};
  std::vector<FileStamp> stamps;
  for (const std::filesystem::path& file : files) {
    const std::optional<FileStamp> stamp = Stamp(file);
    if (!stamp) return Sha256OfFiles(files);  // names the file it cannot open
    stamps.push_back(*stamp);
  }
  const std::string key = std::filesystem::absolute(run_dir).lexically_normal().string();
  {
    std::lock_guard lock(mutex);
    const auto it = known.find(key);
    if (it != known.end() && it->second.first == stamps) return it->second.second;
  }
  const std::string sha = Sha256OfFiles(files);
  const int64_t now_s = static_cast<int64_t>(std::time(nullptr));
  for (size_t i = 0; i < files.size(); ++i) {
    // Changed while read, or too recent to tell a later write apart: keep nothing.
    if (Stamp(files[i]) != stamps[i] || now_s - stamps[i][3] <= kSettled_s) return sha;
  }
  std::lock_guard lock(mutex);
  known[key] = {stamps, sha};
  return sha;
}

namespace {

std::string Sha256OfFiles(const std::vector<std::filesystem::path>& files) {
  common::Sha256 hash;
  for (const std::filesystem::path& path : files) hash.UpdateFile(path);
  return hash.HexDigest();
}

}  // namespace
}  // namespace adahrs::calib
