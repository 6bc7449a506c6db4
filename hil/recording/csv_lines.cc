#include "hil/recording/csv_lines.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include "hil/recording/gzip_reader.h"
#include "hil/recording/recording_files.h"

namespace adahrs::hil {
namespace {

constexpr size_t kBlockBytes = size_t{1} << 20;

}  // namespace

CsvLines::CsvLines(const std::filesystem::path& path) : path_(path), buffer_(kBlockBytes) {
  if (IsCompressed(path_)) {
    gzip_ = std::make_unique<GzipReader>(path_);
    return;
  }
  file_ = std::fopen(path.c_str(), "rb");
  if (file_ == nullptr) {
    throw std::runtime_error(path_.string() + ": cannot open for reading: " + std::strerror(errno));
  }
}

CsvLines::~CsvLines() {
  if (file_ != nullptr) std::fclose(file_);
}

bool CsvLines::stream_truncated() const { return gzip_ != nullptr && gzip_->truncated(); }

bool CsvLines::Refill() {
  if (at_eof_) return false;
  const size_t unread = end_ - begin_;
  if (begin_ > 0) std::memmove(buffer_.data(), buffer_.data() + begin_, unread);
  begin_ = 0;
  end_ = unread;
  if (end_ == buffer_.size()) buffer_.resize(buffer_.size() * 2);  // a line longer than a block
  const size_t got = gzip_ ? gzip_->Read(buffer_.data() + end_, buffer_.size() - end_)
                           : std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
  if (got == 0) {
    if (file_ != nullptr && std::ferror(file_)) {
      throw std::runtime_error(path_.string() + ": read failed: " + std::strerror(errno));
    }
    at_eof_ = true;
    return false;
  }
  end_ += got;
  return true;
}

bool CsvLines::Next(std::string_view& line, bool& complete) {
  size_t searched = begin_;
  for (;;) {
    const void* lf = std::memchr(buffer_.data() + searched, '\n', end_ - searched);
    if (lf != nullptr) {
      const size_t at = static_cast<size_t>(static_cast<const char*>(lf) - buffer_.data());
      line = std::string_view(buffer_.data() + begin_, at - begin_);
      begin_ = at + 1;
      complete = true;
      return true;
    }
    const size_t scanned = end_ - begin_;
    if (!Refill()) break;
    searched = begin_ + scanned;
  }
  if (begin_ == end_) {
    if (!stream_truncated() || truncation_reported_) return false;
    truncation_reported_ = true;  // a member cut between rows: an empty, incomplete last line
    line = std::string_view();
    complete = false;
    return true;
  }
  truncation_reported_ = true;
  line = std::string_view(buffer_.data() + begin_, end_ - begin_);
  begin_ = end_;
  complete = false;
  return true;
}

}  // namespace adahrs::hil
