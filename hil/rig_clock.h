// The virtual rig's simulated clock, shared through a small memory-mapped file (docs/rig.md
// "Clock file"). The rig publishes how many 10 ms world frames it has completed; a pipeline whose
// station names the file (station "clock_file") times every wait, timeout and timestamp on that
// count, so it stays on the rig's timeline however fast or slow a lockstep rig runs.
//
// Layout, 64 bytes, host byte order (both ends run on the same machine):
//   0  char[8]  "ADAHRSCK"         16 f64  frame period, s       32 u64  frames completed
//   8  u32      version (1)        24 f64  nominal time scale    40 i64  writer's pid
// `frames` is written with a release store after the frame's bytes were handed to the ports and
// read with an acquire load.
// Left out: a clock shared across machines; clock adjustment (the rig's time never steps back).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "hil/clock.h"
#include "hil/shared_file_map.h"

namespace adahrs::hil {

/// The writer side: creates (or truncates) the file and publishes the frame count.
class RigClockWriter {
 public:
  /// Throws std::system_error naming the path if the file cannot be created or mapped.
  RigClockWriter(const std::filesystem::path& path, double frame_s, double time_scale);

  void Publish(uint64_t frames_done);
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  SharedFileMap map_;
};

/// Frames in a turn of a unit's 8-bit packet counter (docs/unit-protocol.md).
inline constexpr uint64_t kCounterTurnFrames = 256;

/// A Clock on the rig's published frame count. NowS() is rig seconds since the last whole turn
/// of kCounterTurnFrames frames before this clock was made (0…2.55 s when made): the rig's units
/// sample on its frames and count their packets from its start (docs/rig.md "Clock file"), so the
/// sample time a recording derives from a unit's counter (docs/recording-format.md "Sample time")
/// keeps the rig's phase on this time base instead of a random part of a counter turn.
/// SleepS() waits until the rig's clock has moved that far (it throws std::runtime_error naming
/// the file if the rig's clock stands still for `stall_limit_wall_s` of wall time: a rig that
/// stopped). time_scale() is the rig's nominal speed (a lockstep rig may run slower).
class RigClock : public Clock {
 public:
  /// Throws std::runtime_error naming the path if it is missing, short or not a clock file.
  explicit RigClock(const std::filesystem::path& path, double stall_limit_wall_s = 60.0);

  double NowS() const override;
  void SleepS(double duration_s) const override;
  double time_scale() const override { return time_scale_; }
  bool may_pause() const override { return true; }
  /// Rig seconds since the rig started.
  double RigTimeS() const;

 private:
  uint64_t Frames() const;

  std::filesystem::path path_;
  SharedFileMap map_;
  double frame_s_ = 0.01;
  double time_scale_ = 1.0;
  double start_s_ = 0.0;
  double stall_limit_wall_s_;
};

}  // namespace adahrs::hil
