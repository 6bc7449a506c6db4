#include "hil/recording/csv_file_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <libdeflate.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include "hil/recording/recording_files.h"

namespace adahrs::hil {
namespace {

// A fast rig's rows at a small buffer would cost a write() (or a compression) per few rows.
constexpr size_t kBufferBytes = size_t{1} << 20;

}  // namespace

CsvFileWriter::CsvFileWriter(const std::filesystem::path& path, int gzip_level)
    : path_(path), compressed_(IsCompressed(path)), buffer_(kBufferBytes) {
  if (compressed_) {
    compressor_ = libdeflate_alloc_compressor(gzip_level);
    if (compressor_ == nullptr) {
      throw std::runtime_error(path_.string() + ": cannot make a deflate compressor at level " +
                               std::to_string(gzip_level));
    }
  }
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    libdeflate_free_compressor(compressor_);
    Fail("cannot open for appending");
  }
}

CsvFileWriter::~CsvFileWriter() {
  try {
    Flush();
  } catch (...) {  // a destructor cannot report; Flush before destruction does
  }
  libdeflate_free_compressor(compressor_);
  ::close(fd_);
}

void CsvFileWriter::Fail(const char* what) const {
  throw std::runtime_error(path_.string() + ": " + what + ": " + std::strerror(errno));
}

void CsvFileWriter::WriteAll(const char* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd_, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) Fail("write failed");
    data += n;
    size -= static_cast<size_t>(n);
  }
}

void CsvFileWriter::WriteBuffer() {
  if (buffered_ == 0) return;
  if (!compressed_) {
    WriteAll(buffer_.data(), buffered_);
  } else {
    member_.resize(libdeflate_gzip_compress_bound(compressor_, buffered_));
    const size_t size = libdeflate_gzip_compress(
        compressor_, buffer_.data(), buffered_, member_.data(), member_.size());
    if (size == 0) throw std::runtime_error(path_.string() + ": gzip compression failed");
    WriteAll(member_.data(), size);
  }
  buffered_ = 0;
}

void CsvFileWriter::Append(std::string_view text) {
  if (buffered_ + text.size() > buffer_.size()) {
    WriteBuffer();
    if (text.size() > buffer_.size()) buffer_.resize(text.size());
  }
  std::memcpy(buffer_.data() + buffered_, text.data(), text.size());
  buffered_ += text.size();
}

void CsvFileWriter::Flush() { WriteBuffer(); }

void CsvFileWriter::FlushIfDue() {
  if (!compressed_ || buffered_ >= kMemberBytes) Flush();
}

void CsvFileWriter::Sync() const {
  if (::fsync(fd_) != 0) Fail("fsync failed");
}

}  // namespace adahrs::hil
