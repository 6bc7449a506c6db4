// Reads a text file line by line in large blocks, handing out each line as a view into its own
// buffer (valid until the next call): no allocation per line. A path ending in `.gz` is
// decompressed (gzip_reader.h), any other is read as it is. Says whether a line ended with its
// LF, so a reader can tell a torn last line (a crash mid-row) from a complete one; a compressed
// file whose last gzip member is cut short ends with an incomplete line too (empty when the cut
// fell between rows), so that cut is never passed over in silence. SplitCells cuts a line at its
// commas (no quoting: the recording format has none).
#pragma once

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

namespace adahrs::hil {

class GzipReader;

/// Replaces `cells` with the views of `line`'s comma-separated cells (one more than its commas;
/// an empty line is one empty cell). Scans 16 bytes at a time where SSE2 is available.
void SplitCells(std::string_view line, std::vector<std::string_view>& cells);

class CsvLines {
 public:
  /// Opens `path`; throws std::runtime_error naming it when it cannot be opened.
  explicit CsvLines(const std::filesystem::path& path);
  ~CsvLines();
  CsvLines(const CsvLines&) = delete;
  CsvLines& operator=(const CsvLines&) = delete;

  /// The next line without its LF; false at the end of the file. `complete` is false for a last
  /// line that has no LF.
  bool Next(std::string_view& line, bool& complete);
  /// True for a compressed file whose last member is incomplete (known once Next returned the
  /// last line).
  bool stream_truncated() const;

 private:
  // Moves the unread bytes to the front and reads more; false when nothing more was read.
  bool Refill();

  std::filesystem::path path_;
  std::FILE* file_ = nullptr;         ///< a plain file
  std::unique_ptr<GzipReader> gzip_;  ///< or a compressed one
  bool truncation_reported_ = false;
  std::vector<char> buffer_;
  size_t begin_ = 0;  ///< first unread byte in buffer_
  size_t end_ = 0;    ///< one past the last byte read into buffer_
  bool at_eof_ = false;
};

}  // namespace adahrs::hil
