// The pipeline's notion of time. On real ports the lab runs at wall-clock speed; against a virtual
// rig that runs K times faster than real time (the station file says so) every wait, timeout and
// timestamp the executor derives must shrink by K, or a day-long thermal profile would still take
// a day. Drivers and the executor only ever ask a Clock.
// NowS() is seconds on the run's time base (simulated seconds for a scaled rig), starting at 0
// when the clock is made. SleepS() waits that many clock seconds.
// Against a lockstep rig the station names the rig's clock file and the clock is the rig's own
// (hil/rig_clock.h): it starts at 0 when the run starts, like the others.
#pragma once

#include <chrono>
#include <memory>
#include <string>

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
  /// Whether the clock stands still while its source is held (a lockstep rig waiting for a slow
  /// reader): a reply is then late only once this clock, too, has passed its promised time.
  virtual bool may_pause() const { return false; }
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

/// Wall time after which a reply is late on any clock (a lockstep rig that never moves again).
inline constexpr std::chrono::seconds kMaxReplyWall{60};

/// When a reply promised within `timeout_s` clock seconds is late: once `wall_timeout` of wall
/// time has passed and, on a clock that may pause, `timeout_s` of that clock too (a held rig
/// makes nothing late), or after kMaxReplyWall whatever the clock. Restart() re-arms it (a
/// reader that saw bytes gives the line another timeout).
class ReplyDeadline {
 public:
  ReplyDeadline(const Clock& clock, double timeout_s, std::chrono::milliseconds wall_timeout);
  void Restart();
  bool Passed() const;
  /// How long to wait before asking again: the wall time left, or 10 ms once only the clock's
  /// own deadline is pending (never below 1 ms).
  std::chrono::milliseconds WaitLeft() const;

 private:
  const Clock& clock_;
  double timeout_s_;
  std::chrono::milliseconds wall_timeout_;
  std::chrono::steady_clock::time_point wall_start_;
  double clock_deadline_s_ = 0.0;
};

/// The clock a station asks for: wall clock at scale 1, a scaled clock otherwise.
std::unique_ptr<Clock> MakeClock(double time_scale);
/// The same, or the rig's own clock (hil/rig_clock.h) when `clock_file` is not empty.
std::unique_ptr<Clock> MakeClock(double time_scale, const std::string& clock_file);

}  // namespace adahrs::hil
