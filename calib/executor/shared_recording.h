// The run's RecordingWriter shared by the unit logger threads (rows) and the executor thread
// (meta.json, durable flushes at step boundaries). Rows are handed to a writer thread of their
// own, so a logger thread never waits on the disk: under a fast rig a CSV write can block for
// seconds while the kernel throttles dirty pages (an fsync of a few hundred MB in progress), and a
// logger that stops reading its unit for that long loses packets on the line. The writer thread
// writes each batch and hands it to the kernel as a crash leaves it readable
// (RecordingWriter::FlushIfDue: at once for plain CSV, in gzip members of 256 KiB of text when
// compressed), so a killed process loses only the rows of the last moments (as it loses those
// still on the line); Flush hands every row appended before the call to the kernel and, at step
// boundaries (Flush(true)), fsyncs them (power loss).
// A write error is kept and rethrown by the next Append or Flush, naming the file.
// Left out: a bound on the queue (memory is the buffer; a disk slower than the units for the
// whole run would grow it without limit).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <mutex>
#include <span>
#include <thread>
#include <variant>

#include "hil/recording/recording_writer.h"

namespace adahrs::calib {

class SharedRecording {
 public:
  /// Starts the writer thread; `writer` must outlive this object.
  explicit SharedRecording(hil::RecordingWriter& writer);
  /// Writes what is still queued (errors are dropped: Flush reports them), stops the thread.
  ~SharedRecording();
  SharedRecording(const SharedRecording&) = delete;
  SharedRecording& operator=(const SharedRecording&) = delete;

  template <typename Row>
  void Append(std::span<const Row> rows) {
    if (rows.empty()) return;
    {
      std::lock_guard lock(queue_mutex_);
      RethrowError();
      for (const Row& row : rows) queue_.emplace_back(row);
      queued_ += rows.size();
    }
    queue_cv_.notify_one();
  }
  /// Waits until every row appended before the call has reached the kernel (the gzip members
  /// end); with `durable`, fsyncs them (rows appended meanwhile keep being written).
  void Flush(bool durable);
  void WriteMeta(const hil::RecordingMeta& meta);

 private:
  using Row = std::variant<hil::ImuRecordRow, hil::AdsRecordRow>;
  void WriterLoop();
  void RethrowError() const;  // queue_mutex_ held

  hil::RecordingWriter& writer_;
  std::mutex writer_mutex_;  // the writer's files: rows, meta.json, fsync
  std::mutex queue_mutex_;
  std::condition_variable queue_cv_;    // rows queued or stopping
  std::condition_variable written_cv_;  // rows written
  std::deque<Row> queue_;  // a deque: growing it never moves the queued rows under the lock
  uint64_t queued_ = 0;    // rows ever appended
  uint64_t written_ = 0;   // rows ever written and flushed to the kernel
  bool stopping_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace adahrs::calib
