// Serves a set of virtual devices (rig_sim::SerialDevice) on pseudo-terminals, advancing the rig's
// world in fixed 10 ms frames on a clock that runs `time_scale` times faster than the wall. One
// Boost.Asio thread collects each client's bytes and runs every device per frame (Receive, Advance
// on the shared RigEnvironment, TakeOutput), so the simulated timeline is independent of the time
// scale and of wall-clock jitter; a host that cannot keep up falls behind (frames_behind()) rather
// than skipping frames. Output waits in a per-port backlog sized from kMinBacklogBytes and the
// time scale; a port whose client takes nothing for kClientStallLimit_s is unread and its output
// discarded. Lockstep (SetLockstep) holds the clock while a reading client has more than
// kLockstepBudgetBytes unread, so a slow reader slows the world instead of losing bytes. The clock
// file (SetClockFile, hil/rig_clock.h) publishes the frame count.
// Units: simulated seconds and frames; wall seconds where a name says wall; bytes.
// Frame order, backlog sizes, lockstep's open/progress rules: docs/rig.md ("Time").
// Quantised: the moment a client's bytes are noticed, to the next frame (10 ms simulated).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "hil/rig_clock.h"
#include "hil/rig_port_counts.h"
#include "hil/transport/pty.h"
#include "rig_sim/rig_environment.h"
#include "rig_sim/serial_device.h"

namespace adahrs::rig_sim {

inline constexpr double kWorldFrame_s = 0.01;
/// Bytes per port held for a client that is not reading fast enough before bytes are lost,
/// at time scales up to 5 (scaled up in proportion above, at most 512 times).
inline constexpr size_t kMinBacklogBytes = 64 * 1024;
/// Wall time without reading after which a port counts as unread and its output is discarded.
inline constexpr double kClientStallLimit_s = 2.0;
/// Longest wait between ticks when the host is on time, s.
inline constexpr double kTickLimit_s = 0.002;
/// Lockstep: unread bytes per reading port (host backlog + pty input queue) that hold the clock.
/// A unit port's reader that publishes its packet count (hil/rig_port_counts.h) also holds it
/// while it lags its unit by more than hil::kLockstepPacketBudget packets.
inline constexpr size_t kLockstepBudgetBytes = 16 * 1024;
/// Lockstep: wall time without reading after which a client counts as absent.
inline constexpr double kLockstepStallLimit_s = 5.0;
/// Lockstep: looks at a port's queue (at least one per tick) without it shrinking that, besides
/// the stall limit, make its client count as gone.
inline constexpr uint32_t kLockstepMinLooks = 100;
/// Lockstep: the clock's pace while no client holds any port open, simulated s per wall s.
inline constexpr double kLockstepIdleScale = 1.0;
/// Lockstep: frames between looks at the readers, and the wall wait while one holds the clock.
inline constexpr int kLockstepCheckFrames = 10;
inline constexpr double kLockstepRetry_s = 0.0002;
/// The pty line discipline's input queue (Linux N_TTY_BUF_SIZE), and how close to it the queue
/// counts as full.
inline constexpr size_t kPtyQueueBytes = 4096;
inline constexpr size_t kPtyQueueSlackBytes = 64;

class DeviceHost {
 public:
  /// `time_scale` ≥ 0.01: simulated seconds per wall second.
  explicit DeviceHost(double time_scale, RigEnvironment initial = {});
  ~DeviceHost();
  DeviceHost(const DeviceHost&) = delete;
  DeviceHost& operator=(const DeviceHost&) = delete;

  /// Opens a pty for `device` and returns its slave path. Only before Start().
  std::string Add(std::unique_ptr<SerialDevice> device);

  /// Lockstep mode (see above). Only before Start().
  void SetLockstep(bool on);
  /// Publishes the frame count to `path` (hil::RigClockWriter) from Start() on.
  void SetClockFile(const std::filesystem::path& path);
  bool lockstep() const { return lockstep_; }

  /// Starts the background thread; the simulated clock starts at 0.
  void Start();
  /// Stops the thread (idempotent); devices stay as they were.
  void Stop();

  /// Runs `action` on the host thread between frames, with the devices and environment, and
  /// waits for it (for fault switching and inspection without data races).
  void Run(const std::function<void(std::vector<SerialDevice*>&, RigEnvironment&)>& action);

  /// Simulated time of the last completed frame.
  double now_s() const { return frames_done_.load() * kWorldFrame_s; }
  /// A copy of the environment after the last completed frame.
  RigEnvironment environment() const;
  /// Frames the host was behind the scaled clock at the worst moment so far.
  uint64_t max_frames_behind() const { return max_frames_behind_.load(); }
  uint64_t bytes_lost() const { return bytes_lost_.load(); }
  /// Lockstep: wall seconds the clock was held for a reading client, in all.
  double held_wall_s() const { return held_wall_s_.load(); }
  double time_scale() const { return time_scale_; }
  /// Bytes per port held for a slow client before bytes are lost.
  size_t backlog_limit_bytes() const { return backlog_limit_bytes_; }

  /// One line per port for the rig's exit report: role, the bytes the host discarded on it while
  /// no client read (host_bytes_unread: a line with no listener, expected between runs) and those
  /// it cut beyond the backlog while a client read too slowly (host_bytes_overflowed: a real
  /// loss), and the device's own LineReport; then the worst lag behind the clock.
  /// Taken on the host thread (Run) while it runs, directly once stopped.
  std::vector<std::string> Report();

 private:
  struct Port;
  void ArmRead(Port& port);
  void OnTick();
  // Raises max_frames_behind to `target` - done when that exceeds `tolerance` frames.
  void NoteShortfall(uint64_t target, uint64_t tolerance);
  void RunFrame();
  void Repace(std::chrono::steady_clock::time_point now, double pace);
  void WriteOutputs();
  // Lockstep: true while a reading client has more than the budget unread.
  bool HeldByAReader();
  // Lockstep: true while `port`'s attached reader lags its unit by more than the packet budget.
  bool ReaderLags(Port& port, std::chrono::steady_clock::time_point now);
  // Lockstep: drops the backlog of each port whose reader attached anew, and acknowledges it.
  void NoteAttachments(std::chrono::steady_clock::time_point now);
  // Lockstep: the pty's unread bytes; a client that took bytes since the last look is progress.
  size_t NoteReader(Port& port, std::chrono::steady_clock::time_point now);
  bool ClientReads(const Port& port, std::chrono::steady_clock::time_point now) const;
  // Lockstep: counts the clients holding each port open (inotify on the slave paths).
  void WatchOpens(Port& port);
  void PollOpens();
  void NoteOpens(size_t bytes);
  // True if a client holds `port` open, or if that cannot be known (no watch).
  bool Opened(const Port& port) const;
  bool AnyOpened() const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<std::unique_ptr<Port>> ports_;
  double time_scale_;
  size_t backlog_limit_bytes_;
  RigEnvironment env_;
  mutable std::mutex env_mutex_;
  RigEnvironment env_snapshot_;
  std::atomic<uint64_t> frames_done_{0};
  std::atomic<uint64_t> max_frames_behind_{0};
  std::atomic<uint64_t> bytes_lost_{0};
  std::atomic<double> held_wall_s_{0.0};
  bool lockstep_ = false;
  bool opens_known_ = true;
  std::unique_ptr<hil::RigClockWriter> clock_file_;
  // Lockstep with a clock file: each counted port's packets and its reader's
  // (hil/rig_port_counts.h).
  std::unique_ptr<hil::RigPortCountsWriter> port_counts_;
  void PublishPacketCounts();
  std::thread thread_;
  bool started_ = false;
};

}  // namespace adahrs::rig_sim
