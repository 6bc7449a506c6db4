#include "hil/recording/gzip_reader.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace adahrs::hil {
namespace {

constexpr size_t kInputBytes = size_t{1} << 18;
constexpr int kGzipWindowBits = 16 + MAX_WBITS;  // gzip wrapper only, 32 KiB window

}  // namespace

GzipReader::GzipReader(const std::filesystem::path& path)
    : path_(path), file_(std::fopen(path.c_str(), "rb")), input_(kInputBytes) {
  if (file_ == nullptr) {
    throw std::runtime_error(path_.string() + ": cannot open for reading: " + std::strerror(errno));
  }
  if (inflateInit2(&stream_, kGzipWindowBits) != Z_OK) {
    std::fclose(file_);
    throw std::runtime_error(path_.string() + ": zlib inflateInit2 failed");
  }
}

GzipReader::~GzipReader() {
  inflateEnd(&stream_);
  std::fclose(file_);
}

bool GzipReader::Refill() {
  if (at_eof_) return false;
  const size_t got = std::fread(input_.data(), 1, input_.size(), file_);
  if (got == 0) {
    if (std::ferror(file_)) {
      throw std::runtime_error(path_.string() + ": read failed: " + std::strerror(errno));
    }
    at_eof_ = true;
    return false;
  }
  input_offset_ += got;
  stream_.next_in = input_.data();
  stream_.avail_in = static_cast<uInt>(got);
  return true;
}

size_t GzipReader::Read(char* out, size_t size) {
  size_t produced = 0;
  while (produced < size) {
    if (stream_.avail_in == 0 && !Refill()) {
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
    if (rc == Z_STREAM_END) {
      in_member_ = false;
      complete_bytes_ = input_offset_ - stream_.avail_in;
    } else if (rc != Z_OK && rc != Z_BUF_ERROR) {
      throw std::runtime_error(
          path_.string() + ": corrupt gzip data near compressed byte " +
          std::to_string(input_offset_ - stream_.avail_in) + " (" +
          (stream_.msg != nullptr ? stream_.msg : "zlib error " + std::to_string(rc)) + ")");
    }
  }
  return produced;
}

}  // namespace adahrs::hil
