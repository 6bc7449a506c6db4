#include "hil/recording/csv_lines.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <bit>
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

void SplitCells(std::string_view line, std::vector<std::string_view>& cells) {
  cells.clear();
  const char* cell = line.data();
  const char* c = line.data();
  const char* const end = line.data() + line.size();
#if defined(__SSE2__)
  // A byte at a time costs a compare and a branch per byte of a 150-byte row; sixteen at a time
  // the commas come out of one mask.
  const __m128i comma = _mm_set1_epi8(',');
  for (; end - c >= 16; c += 16) {
    const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(c));
    auto mask = static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(bytes, comma)));
    for (; mask != 0; mask &= mask - 1) {
      const char* at = c + std::countr_zero(mask);
      cells.emplace_back(cell, static_cast<size_t>(at - cell));
      cell = at + 1;
    }
  }
#endif
  for (; c != end; ++c) {
    if (*c != ',') continue;
    cells.emplace_back(cell, static_cast<size_t>(c - cell));
    cell = c + 1;
  }
  cells.emplace_back(cell, static_cast<size_t>(end - cell));
}

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
