#include "calib/executor/shared_recording.h"

namespace adahrs::calib {

SharedRecording::SharedRecording(hil::RecordingWriter& writer)
    : writer_(writer), thread_([this] { WriterLoop(); }) {}

SharedRecording::~SharedRecording() {
  {
    std::lock_guard lock(queue_mutex_);
    stopping_ = true;
  }
  queue_cv_.notify_one();
  thread_.join();
}

void SharedRecording::RethrowError() const {
  if (error_) std::rethrow_exception(error_);
}

void SharedRecording::WriterLoop() {
  std::deque<Row> batch;
  for (;;) {
    {
      std::unique_lock lock(queue_mutex_);
      queue_cv_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping, nothing left
      batch.swap(queue_);
    }
    std::exception_ptr error;
    try {
      std::lock_guard lock(writer_mutex_);
      for (const Row& row : batch) {
        std::visit([&](const auto& r) { writer_.Append(r); }, row);
      }
      writer_.FlushIfDue();
    } catch (...) {
      error = std::current_exception();
    }
    {
      std::lock_guard lock(queue_mutex_);
      written_ += batch.size();
      if (error && !error_) error_ = error;
    }
    written_cv_.notify_all();
    batch.clear();
  }
}

void SharedRecording::Flush(bool durable) {
  {
    std::unique_lock lock(queue_mutex_);
    const uint64_t target = queued_;
    written_cv_.wait(lock, [&] { return written_ >= target; });
    RethrowError();
  }
  {
    std::lock_guard lock(writer_mutex_);
    writer_.Flush(false);  // ends the gzip members: every row so far is readable after a crash
  }
  if (durable) writer_.SyncFlushed();
}

void SharedRecording::WriteMeta(const hil::RecordingMeta& meta) {
  std::lock_guard lock(writer_mutex_);
  writer_.WriteMeta(meta);
}

}  // namespace adahrs::calib
