#include "hil/recording/csv_file_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <libdeflate.h>

#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "hil/recording/recording_files.h"

namespace adahrs::hil {
namespace {

// A fast rig's rows at a small buffer would cost a write() (or a compression) per few rows.
constexpr size_t kBufferBytes = size_t{1} << 20;

}  // namespace

// Compresses one member at a time on a thread of its own and writes it to the file. The appending
// thread hands a full buffer over and takes back the one the thread has finished with, so at most
// one member waits while the next is being filled.
class CsvFileWriter::Compressor {
 public:
  Compressor(CsvFileWriter& file, int gzip_level)
      : file_(file), deflate_(libdeflate_alloc_compressor(gzip_level)) {
    if (deflate_ == nullptr) {
      throw std::runtime_error(file_.path_.string() +
                               ": cannot make a deflate compressor at level " +
                               std::to_string(gzip_level));
    }
    thread_ = std::thread([this] { Run(); });
  }

  ~Compressor() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    cv_.notify_all();
    thread_.join();
    libdeflate_free_compressor(deflate_);
  }

  // Takes the first `size` bytes of `buffer` as the next member; `buffer` comes back as a buffer
  // of no particular content. Waits while the previous member is being compressed.
  void Hand(std::vector<char>& buffer, size_t size) {
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [&] { return !busy_; });
    if (error_) std::rethrow_exception(error_);
    buffer.swap(text_);
    text_size_ = size;
    busy_ = true;
    cv_.notify_all();
  }

  // Waits until every member handed over is written; throws what the thread failed with.
  void Wait() {
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [&] { return !busy_; });
    if (error_) std::rethrow_exception(error_);
  }

 private:
  void Run() {
    std::unique_lock lock(mutex_);
    for (;;) {
      cv_.wait(lock, [&] { return busy_ || stopping_; });
      if (!busy_) return;  // stopping, nothing handed over
      lock.unlock();
      std::exception_ptr error;
      try {
        Compress();
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      if (error && !error_) error_ = error;
      busy_ = false;
      cv_.notify_all();
    }
  }

  void Compress() {
    member_.resize(libdeflate_gzip_compress_bound(deflate_, text_size_));
    const size_t size = libdeflate_gzip_compress(
        deflate_, text_.data(), text_size_, member_.data(), member_.size());
    if (size == 0) throw std::runtime_error(file_.path_.string() + ": gzip compression failed");
    file_.WriteAll(member_.data(), size);
  }

  CsvFileWriter& file_;
  libdeflate_compressor* deflate_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<char> text_;  // the member being compressed (when busy_)
  size_t text_size_ = 0;
  bool busy_ = false;
  bool stopping_ = false;
  std::exception_ptr error_;
  std::vector<char> member_;  // one compressed member
  std::thread thread_;
};

CsvFileWriter::CsvFileWriter(const std::filesystem::path& path, int gzip_level)
    : path_(path), buffer_(kBufferBytes) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) Fail("cannot open for appending");
  if (IsCompressed(path)) {
    try {
      compressor_ = std::make_unique<Compressor>(*this, gzip_level);
    } catch (...) {
      ::close(fd_);
      throw;
    }
  }
}

CsvFileWriter::~CsvFileWriter() {
  try {
    Flush();
  } catch (...) {  // a destructor cannot report; Flush before destruction does
  }
  compressor_.reset();
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
  if (!compressor_) {
    WriteAll(buffer_.data(), buffered_);
  } else {
    compressor_->Hand(buffer_, buffered_);
    if (buffer_.size() < kBufferBytes) buffer_.resize(kBufferBytes);
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

void CsvFileWriter::Flush() {
  WriteBuffer();
  if (compressor_) compressor_->Wait();
}

void CsvFileWriter::FlushIfDue() {
  if (!compressor_) {
    Flush();
  } else if (buffered_ >= kMemberBytes) {
    WriteBuffer();
  }
}

void CsvFileWriter::Sync() const {
  if (::fsync(fd_) != 0) Fail("fsync failed");
}

}  // namespace adahrs::hil
