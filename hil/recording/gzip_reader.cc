#include "hil/recording/gzip_reader.h"

#include <libdeflate.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace adahrs::hil {
namespace {

constexpr size_t kInputBytes = size_t{1} << 22;     // the first window; a member must fit
constexpr size_t kMaxInputBytes = size_t{1} << 26;  // the largest window
constexpr size_t kTextBytes = size_t{1} << 20;      // a writer's member (csv_file_writer.h)
constexpr size_t kMaxTextBytes = size_t{1} << 26;   // larger members stream through zlib
constexpr int kGzipWindowBits = 16 + MAX_WBITS;     // gzip wrapper only, 32 KiB window

}  // namespace

GzipReader::GzipReader(const std::filesystem::path& path)
    : path_(path), file_(std::fopen(path.c_str(), "rb")), input_(kInputBytes), text_(kTextBytes) {
  if (file_ == nullptr) {
    throw std::runtime_error(path_.string() + ": cannot open for reading: " + std::strerror(errno));
  }
  decompressor_ = libdeflate_alloc_decompressor();
  if (decompressor_ == nullptr) {
    std::fclose(file_);
    throw std::runtime_error(path_.string() + ": cannot make a deflate decompressor");
  }
}

GzipReader::~GzipReader() {
  if (streaming_) inflateEnd(&stream_);
  libdeflate_free_decompressor(decompressor_);
  std::fclose(file_);
}

bool GzipReader::FillInput() {
  if (at_eof_) return false;
  if (input_begin_ > 0) {
    std::memmove(input_.data(), input_.data() + input_begin_, input_end_ - input_begin_);
    input_base_ += input_begin_;
    input_end_ -= input_begin_;
    input_begin_ = 0;
  }
  if (input_end_ == input_.size()) {
    if (input_.size() >= kMaxInputBytes) return false;
    input_.resize(input_.size() * 2);
  }
  const size_t got = std::fread(input_.data() + input_end_, 1, input_.size() - input_end_, file_);
  if (got == 0) {
    if (std::ferror(file_)) {
      throw std::runtime_error(path_.string() + ": read failed: " + std::strerror(errno));
    }
    at_eof_ = true;
    return false;
  }
  input_end_ += got;
  return true;
}

bool GzipReader::NextMember() {
  for (;;) {
    if (input_begin_ == input_end_ && !FillInput()) return false;  // the clean end
    size_t in_used = 0;
    size_t out_used = 0;
    const libdeflate_result rc = libdeflate_gzip_decompress_ex(decompressor_,
                                                               input_.data() + input_begin_,
                                                               input_end_ - input_begin_,
                                                               text_.data(),
                                                               text_.size(),
                                                               &in_used,
                                                               &out_used);
    if (rc == LIBDEFLATE_SUCCESS) {
      input_begin_ += in_used;
      complete_bytes_ = input_base_ + input_begin_;
      text_begin_ = 0;
      text_end_ = out_used;
      if (out_used > 0) return true;
      continue;  // an empty member
    }
    if (rc == LIBDEFLATE_INSUFFICIENT_SPACE && text_.size() < kMaxTextBytes) {
      text_.resize(text_.size() * 2);
      continue;
    }
    // Bad data may be a member that goes on past the window: read more and try again.
    if (rc == LIBDEFLATE_BAD_DATA && FillInput()) continue;
    // A member larger than the buffers, cut short by the end of the file, or not a member:
    // zlib streams the rest, reading what there is and naming what is corrupt.
    if (inflateInit2(&stream_, kGzipWindowBits) != Z_OK) {
      throw std::runtime_error(path_.string() + ": zlib inflateInit2 failed");
    }
    streaming_ = true;
    stream_.next_in = input_.data() + input_begin_;
    stream_.avail_in = static_cast<uInt>(input_end_ - input_begin_);
    return false;
  }
}

bool GzipReader::RefillStreaming() {
  input_base_ += input_end_;
  input_begin_ = input_end_ = 0;
  if (!FillInput()) return false;
  stream_.next_in = input_.data();
  stream_.avail_in = static_cast<uInt>(input_end_);
  return true;
}

size_t GzipReader::ReadStreaming(char* out, size_t size) {
  size_t produced = 0;
  while (produced < size) {
    if (stream_.avail_in == 0 && !RefillStreaming()) {
      truncated_ = in_member_;
      break;
    }
    if (!in_member_) {
      inflateReset(&stream_);
      in_member_ = true;
    }
    stream_.next_out = reinterpret_cast<Bytef*>(out + produced);
    stream_.avail_out = static_cast<uInt>(size - produced);
    const int rc = inflate(&stream_, Z_NO_FLUSH);
    produced = size - stream_.avail_out;
    const uint64_t consumed = input_base_ + input_end_ - stream_.avail_in;
    if (rc == Z_STREAM_END) {
      in_member_ = false;
      complete_bytes_ = consumed;
    } else if (rc != Z_OK && rc != Z_BUF_ERROR) {
      throw std::runtime_error(
          path_.string() + ": corrupt gzip data near compressed byte " + std::to_string(consumed) +
          " (" + (stream_.msg != nullptr ? stream_.msg : "zlib error " + std::to_string(rc)) + ")");
    }
  }
  return produced;
}

size_t GzipReader::Read(char* out, size_t size) {
  size_t produced = 0;
  while (produced < size) {
    if (streaming_) return produced + ReadStreaming(out + produced, size - produced);
    if (text_begin_ == text_end_ && !NextMember()) {
      if (streaming_) continue;
      break;
    }
    const size_t n = std::min(size - produced, text_end_ - text_begin_);
    std::memcpy(out + produced, text_.data() + text_begin_, n);
    text_begin_ += n;
    produced += n;
  }
  return produced;
}

}  // namespace adahrs::hil
