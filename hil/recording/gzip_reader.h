// Decompresses a file of one or more gzip members (RFC 1952; a recording's `.csv.gz` holds one
// member per flush, docs/recording-format.md) as one byte stream, in blocks. Knows where the last
// complete member ends, so a file cut short by a crash (its last member without the deflate end
// and CRC trailer) reads up to the cut, says so, and can be truncated back to a clean member
// boundary. Bytes after a complete member that do not start a gzip member are refused, never
// skipped. Left out: gzip's optional header fields are read by zlib and ignored.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace adahrs::hil {

class GzipReader {
 public:
  /// Opens `path`; throws std::runtime_error naming it when it cannot be opened.
  explicit GzipReader(const std::filesystem::path& path);
  ~GzipReader();
  GzipReader(const GzipReader&) = delete;
  GzipReader& operator=(const GzipReader&) = delete;

  /// Decompresses up to `size` bytes into `out`; returns how many, 0 at the end of the file.
  /// Throws std::runtime_error naming the file and the compressed byte offset on corrupt data.
  size_t Read(char* out, size_t size);
  /// True once Read returned 0 on a file whose last member is incomplete (a crash mid-member).
  bool truncated() const { return truncated_; }
  /// Compressed bytes from the start of the file to the end of the last complete member read.
  uint64_t complete_bytes() const { return complete_bytes_; }

 private:
  bool Refill();  // false at the end of the file

  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  z_stream stream_{};
  std::vector<unsigned char> input_;
  uint64_t input_offset_ = 0;  ///< compressed bytes read from the file
  uint64_t complete_bytes_ = 0;
  bool in_member_ = false;  ///< inside a member whose end has not been read
  bool at_eof_ = false;
  bool truncated_ = false;
};

}  // namespace adahrs::hil
