// What every recorded row is annotated with besides the packet itself (docs/recording-format.md):
// the current sequence step, the commanded fixture orientation and the latest instrument readings
// (chamber process value degC, table rate deg/s, ADTS static and impact pressure Pa). The executor
// thread writes them as it commands and reads instruments; the unit logger threads copy a
// consistent snapshot for each batch of packets.
// Left out: the packet's TAG (the logger decides it per packet, unit_logger.h).
#pragma once

#include <mutex>

namespace adahrs::calib {

struct RowAnnotations {
  int step = 0;
  int orientation = 0;  ///< commanded fixture code, 0 before the first mount
  double chamber_c = 0.0;
  double table_rate_dps = 0.0;
  double ps_ref_pa = 0.0;
  double qc_ref_pa = 0.0;
};

/// Thread-safe holder of the current RowAnnotations.
class RunAnnotations {
 public:
  RowAnnotations Get() const {
    std::lock_guard lock(mutex_);
    return current_;
  }
  /// Applies `change` to the annotations under the lock.
  template <typename Change>
  void Update(Change change) {
    std::lock_guard lock(mutex_);
    change(current_);
  }

 private:
  mutable std::mutex mutex_;
  RowAnnotations current_;
};

}  // namespace adahrs::calib
