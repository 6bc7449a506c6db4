#include "hil/recording/csv_file_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include "hil/recording/recording_files.h"

namespace adahrs::hil {
namespace {

// A fast rig's rows at a small buffer would cost a write() (or a deflate call) per few rows.
constexpr size_t kBufferBytes = size_t{1} << 20;
constexpr size_t kDeflatedBytes = size_t{1} << 18;
constexpr int kGzipWindowBits = 16 + MAX_WBITS;  // gzip wrapper, 32 KiB window
constexpr int kMemoryLevel = 8;                  // zlib's default

}  // namespace

CsvFileWriter::CsvFileWriter(const std::filesystem::path& path, int gzip_level)
    : path_(path), compressed_(IsCompressed(path)), buffer_(kBufferBytes) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) Fail("cannot open for appending");
  if (compressed_) {
    deflated_.resize(kDeflatedBytes);
    if (deflateInit2(
            &stream_, gzip_level, Z_DEFLATED, kGzipWindowBits, kMemoryLevel, Z_DEFAULT_STRATEGY) !=
        Z_OK) {
      ::close(fd_);
      throw std::runtime_error(path_.string() + ": zlib deflateInit2 failed");
    }
  }
}

CsvFileWriter::~CsvFileWriter() {
  try {
    Flush();
  } catch (...) {  // a destructor cannot report; Flush before destruction does
  }
  if (compressed_) deflateEnd(&stream_);
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

void CsvFileWriter::Deflate(int flush) {
  stream_.next_in = reinterpret_cast<Bytef*>(buffer_.data());
  stream_.avail_in = static_cast<uInt>(buffered_);
  member_text_bytes_ += buffered_;
  for (;;) {
    stream_.next_out = deflated_.data();
    stream_.avail_out = static_cast<uInt>(deflated_.size());
    const int rc = deflate(&stream_, flush);
    if (rc == Z_STREAM_ERROR) throw std::runtime_error(path_.string() + ": zlib deflate failed");
    WriteAll(reinterpret_cast<const char*>(deflated_.data()), deflated_.size() - stream_.avail_out);
    if (flush == Z_FINISH ? rc == Z_STREAM_END : stream_.avail_out != 0) break;
  }
  buffered_ = 0;
  if (flush == Z_FINISH) {
    deflateReset(&stream_);  // the next text starts a new member
    member_text_bytes_ = 0;
  }
}

void CsvFileWriter::Append(std::string_view text) {
  if (buffered_ + text.size() > buffer_.size()) {
    if (compressed_) {
      Deflate(Z_NO_FLUSH);
    } else {
      WriteAll(buffer_.data(), buffered_);
      buffered_ = 0;
    }
    if (text.size() > buffer_.size()) buffer_.resize(text.size());
  }
  std::memcpy(buffer_.data() + buffered_, text.data(), text.size());
  buffered_ += text.size();
}

void CsvFileWriter::Flush() {
  if (!compressed_) {
    WriteAll(buffer_.data(), buffered_);
    buffered_ = 0;
  } else if (buffered_ > 0 || member_text_bytes_ > 0) {
    Deflate(Z_FINISH);
  }
}

void CsvFileWriter::FlushIfDue() {
  if (!compressed_ || member_text_bytes_ + buffered_ >= kMemberBytes) Flush();
}

void CsvFileWriter::Sync() const {
  if (::fsync(fd_) != 0) Fail("fsync failed");
}

}  // namespace adahrs::hil
