// A clock that continues another from an offset: a resumed run's pipeline clock starts where the
// interrupted run's recording ended, so t_s keeps increasing across the resume.
// Units: clock seconds (simulated seconds on a scaled rig). Left out: nothing else changes; the
// time scale and the sleeps are the base clock's.
#pragma once

#include "hil/clock.h"

namespace adahrs::calib {

class OffsetClock : public hil::Clock {
 public:
  /// NowS() = base.NowS() + offset_s; `base` must outlive this clock.
  OffsetClock(const hil::Clock& base, double offset_s) : base_(base), offset_s_(offset_s) {}
  double NowS() const override { return base_.NowS() + offset_s_; }
  void SleepS(double duration_s) const override { base_.SleepS(duration_s); }
  double time_scale() const override { return base_.time_scale(); }
  bool may_pause() const override { return base_.may_pause(); }

 private:
  const hil::Clock& base_;
  double offset_s_;
};

}  // namespace adahrs::calib
