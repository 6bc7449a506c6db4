// Appends text to one CSV of a recording, plain or gzip-compressed (by the path: `.gz` is
// compressed), through a buffer of its own and a file descriptor opened O_APPEND. A compressed
// file is a series of gzip members (RFC 1952), each compressed whole from the buffer (libdeflate)
// and ending at a row boundary: zlib, Python's gzip module, pandas and zcat read the members as
// one text. Only a complete member is safe from a crash, and compressed text reaches the kernel
// only as complete members: Flush ends the current member, FlushIfDue ends it once it holds
// kMemberBytes of text (small members cost ratio), and a text that does not fit the 1 MiB
// buffer ends it first. Plain text reaches the kernel on either call.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

struct libdeflate_compressor;

namespace adahrs::hil {

class CsvFileWriter {
 public:
  /// Text a compressed member holds before FlushIfDue ends it.
  static constexpr size_t kMemberBytes = size_t{1} << 18;
  /// The deflate level of compressed files (docs/performance.md has the measurement).
  static constexpr int kGzipLevel = 1;

  /// Opens `path` for appending, creating it; a compressed file at deflate level `gzip_level`
  /// (1…9). Throws std::runtime_error naming the path.
  explicit CsvFileWriter(const std::filesystem::path& path, int gzip_level = kGzipLevel);
  ~CsvFileWriter();
  CsvFileWriter(const CsvFileWriter&) = delete;
  CsvFileWriter& operator=(const CsvFileWriter&) = delete;

  /// Buffers `text`, whole rows; writes (compresses) the buffer first when `text` does not fit.
  void Append(std::string_view text);
  /// Hands everything appended to the kernel; a compressed file's member ends here.
  void Flush();
  /// Flush for a plain file; for a compressed one, Flush once the member holds kMemberBytes.
  void FlushIfDue();
  /// Fsyncs what was handed to the kernel; safe to call while another thread appends.
  void Sync() const;

  const std::filesystem::path& path() const { return path_; }

 private:
  void WriteBuffer();  // writes the buffer: plain, or compressed as one member
  void WriteAll(const char* data, size_t size);
  [[noreturn]] void Fail(const char* what) const;

  std::filesystem::path path_;
  int fd_ = -1;
  bool compressed_ = false;
  std::vector<char> buffer_;  ///< text appended and not yet written or compressed
  size_t buffered_ = 0;
  libdeflate_compressor* compressor_ = nullptr;
  std::vector<char> member_;  ///< one compressed member
};

}  // namespace adahrs::hil
