// Decompresses a file of one or more gzip members (RFC 1952; a recording's `.csv.gz` holds one
// member per flush, docs/recording-format.md) as one byte stream. Each member is decompressed
// whole (libdeflate, several times faster than streaming zlib); a member larger than 64 MiB of
// text, a member cut short and anything that is not a member go to streaming zlib, which reads
// what is there. Knows where the last complete member ends, so a file cut short by a crash (its
// last member without the deflate end and CRC trailer) reads up to the cut, says so, and can be
// truncated back to a clean member boundary. Bytes after a complete member that do not start a
// gzip member are refused, never skipped. Left out: gzip's optional header fields are ignored.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <vector>

struct libdeflate_decompressor;

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
  // Whole members: decompresses the next one into text_; false at the end of the file or when
  // the rest of the file goes to zlib (streaming_).
  bool NextMember();
  // Moves the unread input to the front (growing the window when it is full) and reads more of
  // the file; false when nothing more could be read.
  bool FillInput();
  // Streaming zlib from the first unread input byte to the end of the file.
  size_t ReadStreaming(char* out, size_t size);
  bool RefillStreaming();

  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  libdeflate_decompressor* decompressor_ = nullptr;
  std::vector<unsigned char> input_;  ///< a window of the compressed file
  size_t input_begin_ = 0;            ///< first unread byte in input_
  size_t input_end_ = 0;              ///< one past the last byte read into input_
  uint64_t input_base_ = 0;           ///< file offset of input_[0]
  std::vector<char> text_;            ///< the current member's text
  size_t text_begin_ = 0;
  size_t text_end_ = 0;
  bool streaming_ = false;
  z_stream stream_{};
  bool in_member_ = false;  ///< streaming: inside a member whose end has not been read
  uint64_t complete_bytes_ = 0;
  bool at_eof_ = false;
  bool truncated_ = false;
};

}  // namespace adahrs::hil
