// What the executor reports while it runs, for a display to print (the app prints one line per
// report): the step and action in progress, every unit's packet counts and losses, and the ETA
// from the plan's duration estimates. Times are pipeline clock seconds.
// Left out: formatting (the sink decides), wall-clock ETA (divide by the station's time scale).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace adahrs::calib {

struct UnitProgress {
  std::string role;
  std::string serial;
  uint64_t packets = 0;  ///< rows recorded in this session
  int64_t acquired = 0;  ///< packets counted by the acquisition in progress
  uint64_t lost = 0;     ///< lost packets by the sequence counter
};

struct ProgressReport {
  size_t step = 0;  ///< 0-based step index
  size_t step_count = 0;
  std::string step_kind;  ///< "accel", "gyro", …
  size_t action = 0;      ///< 0-based index into the plan
  size_t action_count = 0;
  std::string action_text;  ///< Describe() of the action
  double t_s = 0.0;         ///< pipeline clock
  double eta_s = 0.0;       ///< remaining time by the plan's estimates
  std::vector<UnitProgress> units;
};

class ProgressSink {
 public:
  virtual ~ProgressSink() = default;
  virtual void Report(const ProgressReport& report) = 0;
  /// A notable event (interlock failure, torn row set aside, resume point), one line.
  virtual void Note(const std::string& text) = 0;
};

}  // namespace adahrs::calib
