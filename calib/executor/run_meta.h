// The run's meta.json (docs/recording-format.md "meta.json") as the executor keeps it: built at
// the start of a run (or read back on resume), changed when a rejected interval is added or the
// status changes, and rewritten atomically through the shared recording at every change.
// Left out: validation of a resumed meta.json beyond what resume needs (run_session.cc checks it).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "calib/executor/shared_recording.h"

namespace adahrs::calib {

/// meta.json "status" values.
inline constexpr const char* kStatusRunning = "running";
inline constexpr const char* kStatusComplete = "complete";
inline constexpr const char* kStatusAborted = "aborted";
inline constexpr const char* kStatusInterrupted = "interrupted";

class RunMeta {
 public:
  RunMeta(nlohmann::json meta, SharedRecording& recording)
      : meta_(std::move(meta)), recording_(recording) {}

  const nlohmann::json& json() const { return meta_; }
  /// Writes meta.json now.
  void Write() { recording_.WriteMeta(meta_); }
  void SetStatus(const std::string& status) {
    meta_["status"] = status;
    Write();
  }
  /// Rows with t_start_s <= t_s <= t_end_s are not calibration data.
  void AddRejectedInterval(size_t step,
                           double t_start_s,
                           double t_end_s,
                           const std::string& reason) {
    meta_["rejected_intervals"].push_back(
        {{"step", step}, {"t_start_s", t_start_s}, {"t_end_s", t_end_s}, {"reason", reason}});
    Write();
  }

 private:
  nlohmann::json meta_;
  SharedRecording& recording_;
};

}  // namespace adahrs::calib
