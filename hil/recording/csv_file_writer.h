// Appends text to one CSV of a recording, plain or gzip-compressed (by the path: `.gz` is
// compressed), through a buffer of its own and a file descriptor opened O_APPEND. A compressed
// file is a series of gzip members (RFC 1952), each compressed whole from a buffer (libdeflate)
// and ending at a row boundary: zlib, Python's gzip module, pandas and zcat read the members as
// one text. Compression runs on a thread of the writer's own, one member behind the appending
// thread (a full buffer is handed over and appending goes on in a second one), so formatting and
// compressing a fast rig's rows share two cores. Only a complete member is safe from a crash:
// FlushIfDue ends the current member once it holds kMemberBytes of text (small members cost
// ratio) and hands it to the compressing thread; Flush ends it and returns once every member is
// written; a text that does not fit the 1 MiB buffer ends the member first. Plain text reaches
// the kernel on either call. A failure of the compressing thread (a full disk) is thrown by the
// next call of the appending thread.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

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
  /// Hands everything appended to the kernel (waiting for the compressing thread); a compressed
  /// file's member ends here.
  void Flush();
  /// Flush for a plain file; a compressed one's member ends once it holds kMemberBytes and goes
  /// to the compressing thread (written shortly after; Flush waits for it).
  void FlushIfDue();
  /// Fsyncs what was handed to the kernel; safe to call while another thread appends.
  void Sync() const;

  const std::filesystem::path& path() const { return path_; }

 private:
  class Compressor;
  void WriteBuffer();  // writes the buffer (plain) or hands it to the compressor as one member
  void WriteAll(const char* data, size_t size);
  [[noreturn]] void Fail(const char* what) const;

  std::filesystem::path path_;
  int fd_ = -1;
  std::vector<char> buffer_;  ///< text appended and not yet written or compressed
  size_t buffered_ = 0;
  std::unique_ptr<Compressor> compressor_;  ///< null for a plain file
};

}  // namespace adahrs::hil
