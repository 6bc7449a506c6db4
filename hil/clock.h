// The pipeline's notion of time. On real ports the lab runs at wall-clock speed; against a virtual
// rig that runs K times faster than real time (the station file says so) every wait, timeout and
// timestamp the executor derives must shrink by K, or a day-long thermal profile would still take
// a day. Drivers and the executor only ever ask a Clock.
// NowS() is seconds on the run's time base (simulated seconds for a scaled rig), starting at 0
// when the clock is made. SleepS() waits that many clock seconds.
// Left out: synchronising to the rig's own frame counter (the rig's clock starts when it starts;
// the pipeline's when the run starts; recordings use the pipeline's time base).
#pragma once

#include <chrono>
#include <memory>

namespace adahrs::hil {

class Clock {
 public:
  virtual ~Clock() = default;
  /// Clock seconds since the clock was made.
  virtual double NowS() const = 0;
  /// Waits `duration_s` clock seconds.
  virtual void SleepS(double duration_s) const = 0;
  /// Clock seconds per wall second.
  virtual double time_scale() const = 0;
  /// A wall-clock duration for a timeout of `duration_s` clock seconds (never below 1 ms).
  std::chrono::milliseconds WallTimeout(double duration_s) const;
};

/// Wall-clock time (production PC on real ports): time_scale 1.
class WallClock : public Clock {
 public:
  WallClock();
  double NowS() const override;
  void SleepS(double duration_s) const override;
  double time_scale() const override { return 1.0; }

 private:
  std::chrono::steady_clock::time_point start_;
};

/// Time of a rig that runs `time_scale` times faster than the wall.
class ScaledClock : public Clock {
 public:
  explicit ScaledClock(double time_scale);
  double NowS() const override;
  void SleepS(double duration_s) const override;
  double time_scale() const override { return time_scale_; }

 private:
  std::chrono::steady_clock::time_point start_;
  double time_scale_;
};

/// The clock a station asks for: wall clock at scale 1, a scaled clock otherwise.
std::unique_ptr<Clock> MakeClock(double time_scale);

}  // namespace adahrs::hil
