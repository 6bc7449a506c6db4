#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange under g++ 12

#include "rig_sim/device_host.h"

#include <fmt/format.h>

#include <algorithm>
#include <boost/asio/io_context.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <future>
#include <optional>
#include <stdexcept>

#include <sys/inotify.h>
#include <unistd.h>

#include "rig_sim/pty_clients.h"

namespace adahrs::rig_sim {

// How long a write may take to reach the line discipline's queue (FIONREAD) on a loaded machine:
// beside three CPU hogs the kernel's flip-buffer worker was late by more than 200 ms in 1-2 of 10
// 2.5 s runs; 1 s held in 20 of 20. A reader that drains a full queue is seen at once (it shrank);
// one that keeps it empty is seen this much later, well inside the stall limit.
constexpr std::chrono::milliseconds kFlipGrace{1000};

namespace asio = boost::asio;

struct DeviceHost::Impl {
  asio::io_context io;
  asio::steady_timer timer{io};
  // Opens and closes of the ports' slave paths by clients (non-blocking inotify descriptor, read
  // at every tick; the pairs' own slave descriptors were opened before the watches); -1 if
  // inotify is unavailable.
  int opens_fd = -1;
  std::array<uint8_t, 4096> opens_buffer{};
  ~Impl() {
    if (opens_fd >= 0) ::close(opens_fd);
  }
  // The pace the clock runs at (lockstep: the top speed, or kLockstepIdleScale with no client).
  double pace = 0.0;
  std::chrono::steady_clock::time_point wall_start;
  std::chrono::steady_clock::time_point last_tick;
  bool held = false;  // lockstep: the last tick ended waiting for a reader
  bool stopping = false;
};

struct DeviceHost::Port {
  Port(asio::io_context& io, std::unique_ptr<SerialDevice> d, hil::PtyPair p)
      : device(std::move(d)), pty(std::move(p)), stream(io, ::dup(pty.master_fd())) {}
  std::unique_ptr<SerialDevice> device;
  hil::PtyPair pty;
  asio::posix::stream_descriptor stream;
  std::array<uint8_t, 4096> read_buffer{};
  std::vector<uint8_t> pending_in;
  std::vector<uint8_t> out;
  // Bytes this port's host lost, by cause: discarded while no client read (a line with no
  // listener: expected between runs), or cut beyond the backlog while a client read too slowly.
  uint64_t bytes_unread = 0;
  uint64_t bytes_overflowed = 0;
  // Last wall instant the client took bytes: a client counts as reading while this is recent.
  std::chrono::steady_clock::time_point last_progress;
  // Lockstep: bytes written to the pty in all, the writes of the last kFlipGrace (which may still
  // sit in the kernel's flip buffer, where FIONREAD does not count them), and the most the client
  // is known to have taken (written, less the queue, less those recent writes).
  uint64_t total_written = 0;
  std::deque<std::pair<std::chrono::steady_clock::time_point, uint64_t>> recent_writes;
  uint64_t taken_at_least = 0;
  // Lockstep: the queue at the last look. A queue that shrank between two looks was read: bytes
  // late in the flip buffer can only make it grow.
  size_t unread_at_last_look = 0;
  // Lockstep: looks at the queue since it last shrank. Saturates; starts "long ago" so a port
  // counts as unread until a client reads.
  uint32_t looks_since_progress = kLockstepMinLooks;
  // Clients holding the slave path open (inotify watch `watch`; -1 without one).
  int watch = -1;
  int clients_open = 0;
  // Lockstep with a clock file, a unit port: its slot in the port counts file, the reader's
  // count at the last look and when it last changed.
  std::optional<size_t> count_slot;
  uint64_t reader_token = 0;  // the reader's token acknowledged last
  uint64_t consumed = 0;
  std::chrono::steady_clock::time_point consumed_changed;
  uint32_t count_looks_since_progress = 0;  // looks while it lagged and its count stood still
};

DeviceHost::DeviceHost(double time_scale, RigEnvironment initial)
    : impl_(std::make_unique<Impl>()),
      time_scale_(time_scale),
      backlog_limit_bytes_(static_cast<size_t>(static_cast<double>(kMinBacklogBytes) *
                                               std::clamp(time_scale / 5.0, 1.0, 512.0))),
      env_(initial),
      env_snapshot_(initial) {
  if (!(time_scale >= 0.01)) {
    throw std::invalid_argument("time scale " + std::to_string(time_scale) + " below 0.01");
  }
}

DeviceHost::~DeviceHost() { Stop(); }

void DeviceHost::WatchOpens(Port& port) {
  if (impl_->opens_fd < 0) impl_->opens_fd = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  if (impl_->opens_fd < 0) return;
  port.watch = ::inotify_add_watch(
      impl_->opens_fd, port.pty.slave_path().c_str(), IN_OPEN | IN_CLOSE_WRITE | IN_CLOSE_NOWRITE);
}

void DeviceHost::PollOpens() {
  if (impl_->opens_fd < 0) return;
  for (;;) {
    const ssize_t n =
        ::read(impl_->opens_fd, impl_->opens_buffer.data(), impl_->opens_buffer.size());
    if (n <= 0) return;  // EAGAIN: nothing new
    NoteOpens(static_cast<size_t>(n));
  }
}

void DeviceHost::NoteOpens(size_t n) {
  const auto now = std::chrono::steady_clock::now();
  size_t at = 0;
  while (at + sizeof(inotify_event) <= n) {
    inotify_event event;
    std::memcpy(&event, impl_->opens_buffer.data() + at, sizeof event);
    at += sizeof event + event.len;
    if (event.mask & IN_Q_OVERFLOW) {
      opens_known_ = false;  // events were dropped: the counts are no longer known
      continue;
    }
    for (auto& port : ports_) {
      if (port->watch != event.wd) continue;
      const int before = port->clients_open;
      // Counting events alone miscounts when two identical ones merge: two opens read as one
      // leave the count low, and the first close would then take it to 0 with a client still
      // there. A close's event comes after its descriptor left the table, so at a close the
      // clients are read from /proc (pty_clients.h); an open only adds one (its descriptor may
      // not be in the table yet, and a low count above 0 changes nothing).
      if (event.mask & IN_OPEN) {
        ++port->clients_open;
      } else if (const std::optional<int> clients =
                     CountPtyClients(port->pty.slave_path(), port->pty.slave_fd())) {
        port->clients_open = *clients;
      } else if (port->clients_open > 0) {
        --port->clients_open;
      }
      // A client that opens the port counts as reading from then on (it holds the clock for the
      // stall limit if it never reads).
      if (before == 0 && port->clients_open > 0) {
        port->last_progress = now;
        port->looks_since_progress = 0;
      }
    }
  }
}

bool DeviceHost::Opened(const Port& port) const {
  return !opens_known_ || port.watch < 0 || port.clients_open > 0;
}

bool DeviceHost::AnyOpened() const {
  for (const auto& port : ports_) {
    if (Opened(*port)) return true;
  }
  return false;
}

std::string DeviceHost::Add(std::unique_ptr<SerialDevice> device) {
  if (started_) throw std::logic_error("DeviceHost::Add after Start");
  auto port = std::make_unique<Port>(impl_->io, std::move(device), hil::PtyPair::Open());
  port->stream.non_blocking(true);
  if (lockstep_) WatchOpens(*port);
  std::string path = port->pty.slave_path();
  ports_.push_back(std::move(port));
  return path;
}

void DeviceHost::ArmRead(Port& port) {
  port.stream.async_read_some(
      asio::buffer(port.read_buffer), [this, &port](const boost::system::error_code& ec, size_t n) {
        if (impl_->stopping) return;
        if (!ec) {
          port.pending_in.insert(
              port.pending_in.end(), port.read_buffer.begin(), port.read_buffer.begin() + n);
        }
        // EIO and friends are transient on a pty between client sessions.
        ArmRead(port);
      });
}

void DeviceHost::RunFrame() {
  const double now_s = static_cast<double>(frames_done_.load() + 1) * kWorldFrame_s;
  env_.time_s = now_s;
  for (auto& port : ports_) {
    if (!port->pending_in.empty()) {
      port->device->Receive(port->pending_in, now_s);
      port->pending_in.clear();
    }
    port->device->Advance(now_s, kWorldFrame_s, env_);
  }
  for (auto& port : ports_) port->device->TakeOutput(now_s, port->out);
  frames_done_.fetch_add(1);
}

bool DeviceHost::ClientReads(const Port& port, std::chrono::steady_clock::time_point now) const {
  const double limit_s = lockstep_ ? kLockstepStallLimit_s : kClientStallLimit_s;
  const bool recent = now - port.last_progress <= std::chrono::duration<double>(limit_s);
  if (!lockstep_) return recent;
  // In lockstep a port nobody holds open is not read. One that is open counts as read while its
  // client took bytes within the limit, and also until the host has looked often enough to have
  // seen it read: a host thread that was itself descheduled has no evidence against its readers.
  return Opened(port) && (recent || port.looks_since_progress < kLockstepMinLooks);
}

size_t DeviceHost::NoteReader(Port& port, std::chrono::steady_clock::time_point now) {
  // Only a client takes bytes out of the pty's queue (reading or flushing it): a queue that shrank
  // since the last look was read. Bytes written within kFlipGrace may reach the queue late (the
  // kernel's flip-buffer worker can be descheduled on a loaded machine), so they are counted as
  // still on their way, not as taken: a reader that keeps the queue empty is seen that much later.
  const size_t unread = port.pty.UnreadBytes();
  while (!port.recent_writes.empty() && now - port.recent_writes.front().first > kFlipGrace) {
    port.recent_writes.pop_front();
  }
  uint64_t in_flight = 0;
  for (const auto& [when, bytes] : port.recent_writes) in_flight += bytes;
  const uint64_t in_line = unread + in_flight;
  // A full queue (nobody is reading it now) shows no more than it holds: bytes written beyond it
  // wait in the kernel's flip buffers however old they are, so they are not evidence of a reader.
  const bool queue_full = unread + kPtyQueueSlackBytes >= kPtyQueueBytes;
  const uint64_t taken =
      !queue_full && port.total_written > in_line ? port.total_written - in_line : 0;
  const bool shrank = unread < port.unread_at_last_look;
  port.unread_at_last_look = unread;
  // A client that has taken every byte written is waiting, not stalled: while another port holds
  // the clock its line brings nothing new, and the stall limit must not run out on it meanwhile.
  const bool caught_up = in_line == 0 && port.total_written > 0;
  if (taken > port.taken_at_least || shrank || caught_up) {
    port.taken_at_least = std::max(taken, port.taken_at_least);
    port.last_progress = now;
    port.looks_since_progress = 0;
  } else if (port.looks_since_progress < kLockstepMinLooks) {
    ++port.looks_since_progress;
  }
  return unread;
}

bool DeviceHost::HeldByAReader() {
  const auto now = std::chrono::steady_clock::now();
  if (port_counts_) NoteAttachments(now);
  bool held = false;
  for (auto& port : ports_) {
    const size_t unread = NoteReader(*port, now);
    // An attached reader's lag holds the clock whatever the bytes rules make of the port: its
    // count is exact, and it detaches when it stops reading (or stands still, ReaderLags).
    if (port->count_slot && ReaderLags(*port, now)) held = true;
    if (ClientReads(*port, now) && port->out.size() + unread > kLockstepBudgetBytes) held = true;
  }
  return held;
}

void DeviceHost::NoteAttachments(std::chrono::steady_clock::time_point now) {
  for (auto& port : ports_) {
    if (!port->count_slot) continue;
    const hil::RigPortCountsWriter::Reader reader = port_counts_->ReaderOf(*port->count_slot);
    if (reader.token == 0 || reader.token == port->reader_token) continue;
    // A reader restarted its stream: what waits in the backlog was counted before it, so it goes
    // as a flush of the line would take it (the reader flushes the kernel's queue next), and the
    // stream starts from the count now.
    bytes_lost_ += port->out.size();
    port->bytes_unread += port->out.size();
    port->out.clear();
    const uint64_t start = port->device->DataPacketCount().value_or(0);
    port->reader_token = reader.token;
    port->consumed = start;
    port->consumed_changed = now;
    port->count_looks_since_progress = 0;
    port_counts_->Acknowledge(*port->count_slot, reader.token, start);
  }
}

bool DeviceHost::ReaderLags(Port& port, std::chrono::steady_clock::time_point now) {
  const hil::RigPortCountsWriter::Reader reader = port_counts_->ReaderOf(*port.count_slot);
  if (reader.token == 0 || reader.token != port.reader_token) return false;
  const uint64_t produced = port.device->DataPacketCount().value_or(0);
  const bool lags = produced > reader.consumed + hil::kLockstepPacketBudget;
  // The stall limit runs only while the reader lags without reading: one that has read all it
  // could is waiting, not stalled (another port may hold the clock, so its line brings nothing).
  if (reader.consumed != port.consumed || !lags) {
    port.consumed = reader.consumed;
    port.consumed_changed = now;
    port.count_looks_since_progress = 0;
    return lags;
  }
  if (port.count_looks_since_progress < kLockstepMinLooks) ++port.count_looks_since_progress;
  // A reader that lags without reading for the stall limit, over enough looks that the host
  // itself was not the one descheduled, has stopped: the rig releases its slot, so that the
  // reader, should it come back, finds its packets no longer counted and says so.
  if (now - port.consumed_changed > std::chrono::duration<double>(hil::kLockstepReleaseAfter_s) &&
      port.count_looks_since_progress >= kLockstepMinLooks) {
    port_counts_->Release(*port.count_slot, reader.token);
    port.reader_token = 0;
    return false;
  }
  return true;
}

void DeviceHost::WriteOutputs() {
  const auto now = std::chrono::steady_clock::now();
  for (auto& port : ports_) {
    if (port->out.empty()) continue;
    size_t allowed = port->out.size();
    if (lockstep_) {
      // Only while the line discipline's queue is at most half full, and only up to half of it,
      // so the bytes not yet read stay visible to UnreadBytes() instead of piling up in the
      // kernel's flip buffers, and a write is accepted only once a client has read.
      const size_t unread = NoteReader(*port, now);
      constexpr size_t kHalf = kPtyQueueBytes / 2;
      allowed = std::min(allowed, unread < kHalf ? kHalf - unread : 0);
    }
    boost::system::error_code ec;
    const size_t written =
        allowed == 0 ? 0 : port->stream.write_some(asio::buffer(port->out.data(), allowed), ec);
    if (!ec && written > 0) {
      port->out.erase(port->out.begin(), port->out.begin() + static_cast<std::ptrdiff_t>(written));
      // In lockstep an accepted write says nothing of a client (an empty queue takes bytes with
      // nobody there): only the bytes NoteReader finds taken out of the queue do.
      if (lockstep_) {
        port->total_written += written;
        port->recent_writes.emplace_back(now, written);
      } else {
        port->last_progress = now;
      }
    }
    if (!ClientReads(*port, now)) {
      // Nobody is reading: the bytes go nowhere, as on a line with no listener, so a client
      // that opens the port later (and flushes the kernel's buffer) reads current data.
      bytes_lost_ += port->out.size();
      port->bytes_unread += port->out.size();
      port->out.clear();
    } else if (port->out.size() > backlog_limit_bytes_) {
      bytes_lost_ += port->out.size() - backlog_limit_bytes_;
      port->bytes_overflowed += port->out.size() - backlog_limit_bytes_;
      port->out.resize(backlog_limit_bytes_);
    }
  }
}

// Restarts the pacing from the frames done at `now`, at `pace` simulated s per wall s.
void DeviceHost::Repace(std::chrono::steady_clock::time_point now, double pace) {
  impl_->pace = pace;
  impl_->wall_start =
      now -
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(
          static_cast<double>(frames_done_.load()) * kWorldFrame_s / pace));
}

void DeviceHost::OnTick() {
  if (impl_->stopping) return;
  const auto now = std::chrono::steady_clock::now();
  if (impl_->held)
    held_wall_s_.store(held_wall_s_.load() +
                       std::chrono::duration<double>(now - impl_->last_tick).count());
  impl_->last_tick = now;
  PollOpens();
  // Lockstep with no client on any port: nobody waits for the world, so it runs at real time
  // (at most) instead of simulating at top speed what nobody reads.
  const double pace =
      lockstep_ && !AnyOpened() ? std::min(time_scale_, kLockstepIdleScale) : time_scale_;
  if (pace != impl_->pace) Repace(now, pace);
  const double wall_s = std::chrono::duration<double>(now - impl_->wall_start).count();
  const auto target = static_cast<uint64_t>(wall_s * pace / kWorldFrame_s);
  // Bound the work per tick so reads and control actions interleave with frames.
  bool held = false;
  // With port counts, at most the frames between two looks per tick: a tick's bytes are written
  // before its frames are published, so a reader may see a packet that many frames ahead of the
  // clock (0.1 s; hil::kLockstepLineBuffering_s).
  const int max_frames = port_counts_ ? kLockstepCheckFrames : 200;
  for (int i = 0; i < max_frames && frames_done_.load() < target; ++i) {
    if (lockstep_ && i % kLockstepCheckFrames == 0 && HeldByAReader()) {
      held = true;
      break;
    }
    RunFrame();
  }
  // The clock waited for a reader: restart the pacing from here, so the world does not race to
  // catch up with the wall once the reader is back.
  if (held) Repace(now, pace);
  impl_->held = held;
  {
    // Published before the frames' bytes are written: a client that has read a reply sees the
    // environment that reply describes.
    std::lock_guard<std::mutex> lock(env_mutex_);
    env_snapshot_ = env_;
  }
  // Also before the bytes are written: a reader that has read a packet finds it counted.
  PublishPacketCounts();
  WriteOutputs();
  if (clock_file_) clock_file_->Publish(frames_done_.load());
  if (!held) NoteShortfall(target, 0);
  if (!held && frames_done_.load() < target) {
    // Behind the clock: continue at once (reads and posted actions still interleave) instead of
    // sleeping on the timer, whose wake-up latency on a loaded machine would set the pace.
    asio::post(impl_->io, [this] { OnTick(); });
    return;
  }
  const auto wall_per_frame = std::chrono::duration<double>(kWorldFrame_s / pace);
  const auto wait = held ? std::chrono::duration<double>(kLockstepRetry_s)
                         : std::min(wall_per_frame, std::chrono::duration<double>(kTickLimit_s));
  impl_->timer.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(wait));
  impl_->timer.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) OnTick();
  });
}

void DeviceHost::SetLockstep(bool on) {
  if (started_) throw std::logic_error("DeviceHost::SetLockstep after Start");
  lockstep_ = on;
  for (auto& port : ports_) {
    if (on && port->watch < 0) WatchOpens(*port);
  }
}

void DeviceHost::SetClockFile(const std::filesystem::path& path) {
  if (started_) throw std::logic_error("DeviceHost::SetClockFile after Start");
  clock_file_ = std::make_unique<hil::RigClockWriter>(path, kWorldFrame_s, time_scale_);
}

void DeviceHost::PublishPacketCounts() {
  if (!port_counts_) return;
  for (const auto& port : ports_) {
    if (port->count_slot)
      port_counts_->PublishProduced(*port->count_slot, port->device->DataPacketCount().value_or(0));
  }
}

void DeviceHost::Start() {
  if (started_) return;
  started_ = true;
  if (clock_file_) {
    // Counts only in lockstep, where the hold bounds a reader's lag; a file left by an earlier
    // lockstep rig would mislead this one's readers.
    const std::filesystem::path path = hil::PortCountsPath(clock_file_->path());
    std::filesystem::remove(path);
    if (lockstep_) {
      std::vector<std::string> counted;
      for (auto& port : ports_) {
        if (!port->device->DataPacketCount()) continue;
        port->count_slot = counted.size();
        counted.push_back(port->pty.slave_path());
      }
      port_counts_ = std::make_unique<hil::RigPortCountsWriter>(path, counted);
    }
  }
  for (auto& port : ports_) ArmRead(*port);
  asio::post(impl_->io, [this] {
    // The clock starts when the frame thread runs, not when it was asked to.
    impl_->wall_start = std::chrono::steady_clock::now();
    impl_->last_tick = impl_->wall_start;
    impl_->pace = time_scale_;
    // Free-running, every port starts as read; in lockstep none does until a client reads, so
    // a port nobody opens never holds the clock.
    const auto never =
        impl_->wall_start - std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                std::chrono::duration<double>(kLockstepStallLimit_s + 1.0));
    for (auto& port : ports_) port->last_progress = lockstep_ ? never : impl_->wall_start;
    OnTick();
  });
  thread_ = std::thread([this] { impl_->io.run(); });
}

void DeviceHost::NoteShortfall(uint64_t target, uint64_t tolerance) {
  const uint64_t done = frames_done_.load();
  if (target > done + tolerance && target - done > max_frames_behind_.load()) {
    max_frames_behind_.store(target - done);
  }
}

void DeviceHost::Stop() {
  if (!started_ || !thread_.joinable()) return;
  asio::post(impl_->io, [this] {
    // A host starved just before the stop never ran the tick that would have noticed: count the
    // frames the clock owed at the stop, beyond what one tick's pacing leaves undone.
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - impl_->wall_start).count();
    const double frames_per_tick = kTickLimit_s * impl_->pace / kWorldFrame_s;
    NoteShortfall(static_cast<uint64_t>(wall_s * impl_->pace / kWorldFrame_s),
                  static_cast<uint64_t>(std::ceil(frames_per_tick)) + 1);
    impl_->stopping = true;
    impl_->timer.cancel();
    for (auto& port : ports_) port->stream.cancel();
  });
  thread_.join();
}

void DeviceHost::Run(
    const std::function<void(std::vector<SerialDevice*>&, RigEnvironment&)>& action) {
  std::vector<SerialDevice*> devices;
  for (auto& port : ports_) devices.push_back(port->device.get());
  if (!started_ || !thread_.joinable()) {
    action(devices, env_);
    return;
  }
  std::promise<void> done;
  asio::post(impl_->io, [&] {
    try {
      action(devices, env_);
      done.set_value();
    } catch (...) {
      done.set_exception(std::current_exception());
    }
  });
  done.get_future().get();
}

std::vector<std::string> DeviceHost::Report() {
  std::vector<std::string> lines;
  uint64_t unread = 0, overflowed = 0;
  Run([&](std::vector<SerialDevice*>&, RigEnvironment&) {
    for (const auto& port : ports_) {
      unread += port->bytes_unread;
      overflowed += port->bytes_overflowed;
      const std::string device = port->device->LineReport();
      lines.push_back(fmt::format("{:<14} host_bytes_unread={} host_bytes_overflowed={}{}{}",
                                  port->device->role(),
                                  port->bytes_unread,
                                  port->bytes_overflowed,
                                  device.empty() ? "" : " ",
                                  device));
    }
  });
  lines.push_back(fmt::format(
      "host: {} bytes discarded with no client reading, {} bytes cut beyond the backlog "
      "while a client read; worst lag {} frames ({:.2f} s simulated)",
      unread,
      overflowed,
      max_frames_behind_.load(),
      static_cast<double>(max_frames_behind_.load()) * kWorldFrame_s));
  if (lockstep_) {
    lines.push_back(fmt::format("host: lockstep, clock held {:.2f} s of wall time for its readers",
                                held_wall_s_.load()));
  }
  return lines;
}

RigEnvironment DeviceHost::environment() const {
  std::lock_guard<std::mutex> lock(env_mutex_);
  return env_snapshot_;
}

}  // namespace adahrs::rig_sim
