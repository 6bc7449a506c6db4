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

#include <openssl/evp.h>

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
  const std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(),
                                                                    &EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error("RecordingSha256: OpenSSL SHA-256 initialisation failed");
  }
  for (const std::filesystem::path& path : files) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path.string() + ": cannot open for the recording checksum");
    std::array<char, 1 << 16> buffer;
    while (in) {
      in.read(buffer.data(), buffer.size());
      if (in.gcount() > 0 &&
          EVP_DigestUpdate(ctx.get(), buffer.data(), static_cast<size_t>(in.gcount())) != 1) {
        throw std::runtime_error(path.string() + ": SHA-256 update failed");
      }
    }
    if (in.bad()) throw std::runtime_error(path.string() + ": read error");
  }
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  if (EVP_DigestFinal_ex(ctx.get(), digest.data(), &length) != 1) {
    throw std::runtime_error("RecordingSha256: SHA-256 finalisation failed");
  }
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) {
    hex += kHex[digest[i] >> 4];
    hex += kHex[digest[i] & 0xF];
  }
  return hex;
}

}  // namespace
}  // namespace adahrs::calib
