// The run's RecordingWriter shared by the unit logger threads (rows) and the executor thread
// (meta.json, durable flushes at step boundaries): one mutex around the writer. Each batch of
// rows is flushed to the kernel as it is appended, so a killed process loses no row it received;
// the fsync (power loss) happens at step boundaries.
// Left out: any buffering of its own; the writer's stdio buffers suffice.
#pragma once

#include <mutex>
#include <span>

#include "hil/recording/recording_writer.h"

namespace adahrs::calib {

class SharedRecording {
 public:
  explicit SharedRecording(hil::RecordingWriter& writer) : writer_(writer) {}

  template <typename Row>
  void Append(std::span<const Row> rows) {
    std::lock_guard lock(mutex_);
    if (rows.empty()) return;
    for (const Row& row : rows) writer_.Append(row);
    writer_.Flush(false);
  }
  /// Flushes under the lock; with `durable`, fsyncs after releasing it (rows keep coming).
  void Flush(bool durable) {
    {
      std::lock_guard lock(mutex_);
      writer_.Flush(false);
    }
    if (durable) writer_.SyncFlushed();
  }
  void WriteMeta(const nlohmann::json& meta) {
    std::lock_guard lock(mutex_);
    writer_.WriteMeta(meta);
  }

 private:
  std::mutex mutex_;
  hil::RecordingWriter& writer_;
};

}  // namespace adahrs::calib
