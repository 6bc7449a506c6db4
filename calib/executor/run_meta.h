// The run's meta.json (docs/recording-format.md "meta.json") as the executor keeps it: built at
// the start of a run (or read back on resume), changed when a rejected interval is added or the
// status changes, and rewritten atomically through the shared recording at every change.
// Left out: validation of a resumed meta.json beyond what resume needs (run_session.cc checks it).
#pragma once

#include <string>

#include "calib/executor/shared_recording.h"
#include "hil/recording/recording_meta.h"

namespace adahrs::calib {

/// meta.json "status" values.
inline constexpr const char* kStatusRunning = "running";
inline constexpr const char* kStatusComplete = "complete";
inline constexpr const char* kStatusAborted = "aborted";
inline constexpr const char* kStatusInterrupted = "interrupted";

class RunMeta {
 public:
  RunMeta(hil::RecordingMeta meta, SharedRecording& recording)
      : meta_(std::move(meta)), recording_(recording) {}

  const hil::RecordingMeta& meta() const { return meta_; }
  /// Writes meta.json now.
  void Write() { recording_.WriteMeta(meta_); }
  void SetStatus(const std::string& status) {
    meta_.status = status;
    Write();
  }
  /// Rows with t_start_s <= t_s <= t_end_s are not calibration data.
  void AddRejectedInterval(size_t step,
                           double t_start_s,
                           double t_end_s,
                           const std::string& reason) {
    meta_.rejected_intervals.push_back({static_cast<int>(step), t_start_s, t_end_s, reason});
    meta_.has_rejected_intervals = true;
    Write();
  }

 private:
  hil::RecordingMeta meta_;
  SharedRecording& recording_;
};

}  // namespace adahrs::calib
