// The host in lockstep: a reader slower than the world holds the clock instead of losing bytes;
// a port nobody holds open never holds it, one whose client stopped reading holds it for
// kLockstepStallLimit_s; with no client at all the clock runs at real time; the clock file follows.
#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "hil/rig_clock.h"
#include "hil/rig_port_counts.h"
#include "rig_sim/device_host.h"

namespace adahrs::rig_sim {
namespace {

// A divisor of the host's lockstep writes (half the pty queue), so no record is torn when the
// host discards what it sent before a client read.
constexpr size_t kFrameBytes = 32;

// Sends `records_per_frame` 32-byte records per world frame, each the record's index (u32, host
// order) and 28 bytes of its low byte, so a reader can tell a lost, repeated or torn record.
class FrameStream : public SerialDevice {
 public:
  explicit FrameStream(std::string role = "stream", uint32_t records_per_frame = 1)
      : role_(std::move(role)), records_per_frame_(records_per_frame) {}
  const std::string& role() const override { return role_; }
  void Receive(std::span<const uint8_t>, double) override {}
  void Advance(double, double, RigEnvironment&) override {}
  void TakeOutput(double, std::vector<uint8_t>& out) override {
    for (uint32_t i = 0; i < records_per_frame_; ++i) {
      ++record_;
      uint8_t record[kFrameBytes];
      std::memcpy(record, &record_, sizeof record_);
      std::memset(
          record + sizeof record_, static_cast<int>(record_ & 0xff), kFrameBytes - sizeof record_);
      out.insert(out.end(), record, record + kFrameBytes);
    }
  }

 private:
  std::string role_;
  uint32_t records_per_frame_;
  uint32_t record_ = 0;
};

// A FrameStream that counts its records as a unit counts its data packets (the rig's port counts:
// rig_sim/serial_device.h DataPacketCount), one per world frame: record r is packet r - 1.
class CountedStream : public FrameStream {
 public:
  explicit CountedStream(std::string role) : FrameStream(std::move(role), 1) {}
  void TakeOutput(double t_s, std::vector<uint8_t>& out) override {
    FrameStream::TakeOutput(t_s, out);
    ++count_;
  }
  std::optional<uint64_t> DataPacketCount() const override { return count_; }

 private:
  uint64_t count_ = 0;
};

int OpenRaw(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
  termios tio{};
  ::tcgetattr(fd, &tio);
  ::cfmakeraw(&tio);
  ::tcsetattr(fd, TCSANOW, &tio);
  return fd;
}

// Reads records slowly (512 bytes, then a 2 ms nap: about 250 kB/s, far below the 2000x world's
// 6.4 MB/s) and checks that they are consecutive once it reads (what the host sent before a client
// first read is discarded, as on a line with no listener).
struct SlowReader {
  std::chrono::milliseconds nap{2};
  bool drain = false;  // read all there is before each nap, as a logger polling its port does
  std::atomic<int> pause_ms{0};  // one longer nap, as of a logger descheduled on a loaded machine
  std::atomic<bool> stop{false};
  uint64_t first = 0;                 // the first frame index read (records count from 1)
  uint64_t records = 0;               // the last frame index read
  std::atomic<uint64_t> read = 0;     // records read (watched while it runs)
  uint64_t out_of_order = 0;          // torn or going back
  std::atomic<uint64_t> skipped = 0;  // records skipped
  void Run(int fd) {
    std::vector<uint8_t> pending;
    uint8_t buffer[512];
    while (!stop.load()) {
      ssize_t n = 0;
      do {
        n = ::read(fd, buffer, sizeof buffer);
        if (n > 0) pending.insert(pending.end(), buffer, buffer + n);
      } while (drain && n > 0);
      while (pending.size() >= kFrameBytes) {
        uint32_t frame = 0;
        std::memcpy(&frame, pending.data(), sizeof frame);
        const bool torn = pending[kFrameBytes - 1] != (frame & 0xff);
        if (torn || (read > 0 && frame <= records)) ++out_of_order;
        if (read > 0 && frame > records + 1) skipped += frame - records - 1;
        if (read == 0) first = frame;
        records = frame;
        ++read;
        pending.erase(pending.begin(), pending.begin() + kFrameBytes);
      }
      std::this_thread::sleep_for(nap);
      if (const int ms = pause_ms.exchange(0); ms > 0) {
        std::this_thread::sleep_for(std::chrono::milliseconds(ms));
      }
    }
  }
};

TEST(DeviceHostLockstep, SlowReaderHoldsTheClockAndLosesNothing) {
  DeviceHost host(2000.0);
  host.SetLockstep(true);
  const std::string path = host.Add(std::make_unique<FrameStream>());
  const int fd = OpenRaw(path);
  ASSERT_GE(fd, 0);
  host.Start();
  SlowReader reader;
  std::thread thread([&] { reader.Run(fd); });
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  reader.stop = true;
  thread.join();
  host.Stop();
  ::close(fd);
  EXPECT_EQ(reader.out_of_order, 0u);
  // Nothing lost once the reader read: the host discards only until it has seen a first read
  // (device_host.cc: a port counts as unread until then) or after a reader took nothing for
  // kLockstepStallLimit_s, and this one reads every few ms. So the records before the first read
  // are the host's whole loss, by its own count, and none is missing after it.
  EXPECT_EQ(reader.skipped.load(), 0u);
  EXPECT_EQ(host.bytes_lost(), (reader.first - 1) * kFrameBytes);
  EXPECT_GT(reader.records, 1000u);
  // The world ran only as far as the reader read, plus what lockstep lets wait: the budget, the
  // pty's queue, one look's worth of frames, and up to another queue's worth written while the
  // kernel had not yet moved earlier writes into the queue (a flip-buffer worker descheduled on a
  // loaded machine: seen once, 58 frames beyond the first three).
  const double frames = host.now_s() / kWorldFrame_s;
  const double waiting =
      static_cast<double>(kLockstepBudgetBytes + 2 * kPtyQueueBytes) / kFrameBytes +
      kLockstepCheckFrames;
  EXPECT_LE(frames - static_cast<double>(reader.records), waiting);
  EXPECT_LT(frames, 0.5 * 2000.0 * 1.5 / kWorldFrame_s) << "the clock did not wait";
  EXPECT_GT(host.held_wall_s(), 0.5);
}

TEST(DeviceHostLockstep, PortNobodyOpensNeverHoldsTheClock) {
  DeviceHost host(1000.0);
  host.SetLockstep(true);
  host.Add(std::make_unique<FrameStream>("unopened"));
  const std::string read_path = host.Add(std::make_unique<FrameStream>("read"));
  const int fd = OpenRaw(read_path);
  ASSERT_GE(fd, 0);
  host.Start();
  SlowReader reader;
  reader.nap = std::chrono::milliseconds(1);
  reader.drain = true;
  std::thread reader_thread([&] { reader.Run(fd); });
  // Longer than the rig's grace for bytes on their way into the queue, so writes age out of it.
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  reader.stop = true;
  reader_thread.join();
  host.Stop();
  ::close(fd);
  // ~2500 s at 1000x with a reader on the other port; far past the budget's 4 s of this stream.
  EXPECT_GT(host.now_s(), 100.0);
  EXPECT_GT(host.bytes_lost(), 0u);  // the unopened port's bytes, discarded: nobody listens
  EXPECT_EQ(reader.skipped.load(), 0u);
}

TEST(DeviceHostLockstep, WithNoClientOnAnyPortTheClockRunsAtRealTime) {
  DeviceHost host(1000.0);
  host.SetLockstep(true);
  host.Add(std::make_unique<FrameStream>());
  host.Start();
  const auto start = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  host.Stop();
  // kLockstepIdleScale (1x): at most the wall time (plus the frame in progress), never 1000x.
  EXPECT_LE(host.now_s(), wall_s * kLockstepIdleScale + 2 * kWorldFrame_s);
  EXPECT_GT(host.now_s(), 0.3);  // it runs: a loaded machine may start the thread late
  EXPECT_EQ(host.held_wall_s(), 0.0);
}

// Reads `fd` for `wall_ms`: a client that takes over the line and reads what arrives.
void ReadFor(int fd, int wall_ms) {
  ::tcflush(fd, TCIFLUSH);
  uint8_t buffer[4096];
  const auto read_until = std::chrono::steady_clock::now() + std::chrono::milliseconds(wall_ms);
  while (std::chrono::steady_clock::now() < read_until) {
    if (::read(fd, buffer, sizeof buffer) <= 0)
      std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

TEST(DeviceHostLockstep, ClientThatStopsReadingHoldsTheClockForTheStallLimit) {
  DeviceHost host(1000.0);
  host.SetLockstep(true);
  const std::string path = host.Add(std::make_unique<FrameStream>());
  host.Start();
  const int fd = OpenRaw(path);
  ASSERT_GE(fd, 0);
  ReadFor(fd, 300);
  // The client keeps the port open and reads no more (a hung logger).
  std::this_thread::sleep_for(std::chrono::duration<double>(kLockstepStallLimit_s * 0.5));
  const double held_s = host.now_s();
  std::this_thread::sleep_for(std::chrono::duration<double>(kLockstepStallLimit_s * 0.5 + 1.5));
  host.Stop();
  ::close(fd);
  // Held at the budget (~5 s of this stream after the client stopped), then the port counts as
  // unread and the world runs on at top speed (a client still holds it open).
  EXPECT_GT(host.held_wall_s(), 0.5 * kLockstepStallLimit_s);
  EXPECT_GT(host.now_s(), held_s + 100.0);
}

TEST(DeviceHostLockstep, ClientThatClosesThePortReleasesTheClockAtOnce) {
  // 100x: slow enough that the other port's reader never holds the clock itself.
  DeviceHost host(100.0);
  host.SetLockstep(true);
  const std::string leaving_path = host.Add(std::make_unique<FrameStream>("leaving"));
  const std::string read_path = host.Add(std::make_unique<FrameStream>("read"));
  const int read_fd = OpenRaw(read_path);
  ASSERT_GE(read_fd, 0);
  host.Start();
  SlowReader reader;
  reader.nap = std::chrono::milliseconds(1);
  reader.drain = true;
  std::thread reader_thread([&] { reader.Run(read_fd); });
  const int fd = OpenRaw(leaving_path);
  ASSERT_GE(fd, 0);
  ReadFor(fd, 300);
  ::close(fd);
  const double left_s = host.now_s();
  const double held_before_s = host.held_wall_s();
  std::this_thread::sleep_for(std::chrono::duration<double>(kLockstepStallLimit_s * 0.5));
  reader.stop = true;
  reader_thread.join();
  host.Stop();
  ::close(read_fd);
  // The closed port holds nothing: the clock runs on for the other port's reader at once (a
  // loaded machine may hold it a little for that reader). Held for the stall limit, it would
  // have stood still through this whole wait.
  EXPECT_LT(host.held_wall_s() - held_before_s, 0.25 * kLockstepStallLimit_s);
  EXPECT_GT(host.now_s(), left_s + 100.0);  // 250 s at 100x
  EXPECT_EQ(reader.skipped.load(), 0u);
}

// Two clients of one port opened back to back, as a campaign's identity check and its bench open
// a unit's port (inotify merges identical events not yet read, so the two opens may reach the
// host as one): when the first closes, the second still holds the port open, and every record the
// host sends from then on reaches it. Counting open and close events alone, the host took the port
// for closed and dropped its output while the second client read nothing.
TEST(DeviceHostLockstep, SecondClientOfAPortKeepsReceivingWhenTheFirstCloses) {
  DeviceHost host(100.0);
  host.SetLockstep(true);
  const std::string path = host.Add(std::make_unique<FrameStream>("shared"));
  host.Start();
  for (int round = 0; round < 10; ++round) {
    SCOPED_TRACE(round);
    const int first = OpenRaw(path);
    const int second = OpenRaw(path);
    ASSERT_GE(first, 0);
    ASSERT_GE(second, 0);
    SlowReader reader;
    reader.nap = std::chrono::milliseconds(1);
    reader.drain = true;
    std::thread reader_thread([&] { reader.Run(second); });
    // Until the host has seen the opens it sends to nobody (what a client reads first may be
    // followed by a gap, as on a line it just opened): the first client closes once the second
    // reads, and only what follows the close is judged.
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    const uint64_t read_before = reader.read.load();
    const uint64_t skipped_before = reader.skipped.load();
    ::close(first);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    reader.stop = true;
    reader_thread.join();
    ::close(second);
    // 0.3 s wall at 100x is 3,000 world frames, a record each; a tenth of that allows a loaded
    // machine. A port taken for closed passes on only what its queue held: under 70 records.
    EXPECT_GT(reader.read.load() - read_before, 300u);
    EXPECT_EQ(reader.skipped.load(), skipped_before);
    EXPECT_EQ(reader.out_of_order, 0u);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  host.Stop();
}

// A logger that has read all its port had is waiting, not gone, however long another port (whose
// client went away) holds the clock: descheduled for 2 s just as the clock runs again, it loses
// nothing.
TEST(DeviceHostLockstep, ReaderOfAnotherPortLosesNothingWhileAGoneClientHoldsTheClock) {
  DeviceHost host(1000.0);
  host.SetLockstep(true);
  const std::string gone_path = host.Add(std::make_unique<FrameStream>("gone", 32));
  const std::string kept_path = host.Add(std::make_unique<FrameStream>("kept", 1));
  const int gone_fd = OpenRaw(gone_path);
  const int kept_fd = OpenRaw(kept_path);
  ASSERT_GE(gone_fd, 0);
  ASSERT_GE(kept_fd, 0);
  host.Start();
  SlowReader gone;
  gone.nap = std::chrono::milliseconds(0);
  SlowReader kept;
  kept.nap = std::chrono::milliseconds(10);
  kept.drain = true;
  std::thread gone_thread([&] { gone.Run(gone_fd); });
  std::thread kept_thread([&] { kept.Run(kept_fd); });
  // What the host discarded before it saw a reader is not at issue here: only what follows.
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  gone.stop = true;
  gone_thread.join();
  const double left_s = host.now_s();
  const uint64_t skipped_before = kept.skipped.load();
  std::this_thread::sleep_for(std::chrono::duration<double>(kLockstepStallLimit_s - 0.5));
  kept.pause_ms = 2000;
  std::this_thread::sleep_for(std::chrono::milliseconds(3500));
  kept.stop = true;
  kept_thread.join();
  host.Stop();
  ::close(gone_fd);
  ::close(kept_fd);
  EXPECT_GT(host.held_wall_s(), 0.8 * kLockstepStallLimit_s) << "the gone client held nothing";
  EXPECT_GT(host.now_s(), left_s + 1.0) << "the clock never ran again";
  EXPECT_EQ(kept.out_of_order, 0u);
  EXPECT_EQ(kept.skipped.load() - skipped_before, 0u) << "the kept port's reader lost records";
  EXPECT_GT(kept.read.load(), 100u);
}

// Reads a CountedStream's port as a unit link does: drains it, loads the rig's count after each
// read (its lag behind the unit: that count less what it had published before), publishes the
// last whole record read as its count.
struct CountedReader {
  hil::RigPortCounter* counter = nullptr;
  std::atomic<bool> stop{false};
  std::atomic<int> pause_ms{0};  // one long nap, as of a logger descheduled on a loaded machine
  std::atomic<uint64_t> worst_lag{0}, reads{0};
  void Run(int fd) {
    std::vector<uint8_t> pending;
    uint8_t buffer[512];
    uint64_t consumed = counter->Consumed();  // where the rig started the stream
    while (!stop.load()) {
      ssize_t n = 0;
      bool got = false;
      while ((n = ::read(fd, buffer, sizeof buffer)) > 0) {
        pending.insert(pending.end(), buffer, buffer + n);
        got = true;
      }
      if (got) {
        const uint64_t produced = counter->Produced();
        if (produced > consumed) worst_lag = std::max(worst_lag.load(), produced - consumed);
        for (; pending.size() >= kFrameBytes;
             pending.erase(pending.begin(), pending.begin() + kFrameBytes)) {
          uint32_t record = 0;
          std::memcpy(&record, pending.data(), sizeof record);
          consumed = record;
        }
        counter->Consume(consumed);
        ++reads;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      if (const int ms = pause_ms.exchange(0); ms > 0)
        std::this_thread::sleep_for(std::chrono::milliseconds(ms));
    }
  }
};

// A lockstep host with a clock file (so it publishes port counts) in a directory of its own.
struct CountingHost {
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("adahrs-counts-" + std::to_string(::getpid()));
  DeviceHost host;
  explicit CountingHost(double time_scale) : host(time_scale) {
    std::filesystem::create_directories(dir);
    host.SetLockstep(true);
    host.SetClockFile(dir / "clock");
  }
  ~CountingHost() { std::filesystem::remove_all(dir); }
  std::unique_ptr<hil::RigPortCounter> Counter(const std::string& path) const {
    return hil::RigPortCounter::Open(dir / "clock", path);
  }
};

// A counted reader (hil/rig_port_counts.h) that has read all its port had is waiting, not stalled,
// however long another port's gone client holds the clock: descheduled for 2 s just as the clock
// runs again, it is still held to, never more than the packet budget and the frames between two
// looks behind its unit when it reads again. A rig that took the wait for a stall would run on to
// the bytes rule's 16 KiB (500 records here): more than a counter turn, so its packets would be
// placed whole turns late.
TEST(DeviceHostLockstep, CountedReaderStaysHeldAfterAnotherPortHeldTheClock) {
  CountingHost rig(1000.0);
  DeviceHost& host = rig.host;
  const std::string gone_path = host.Add(std::make_unique<FrameStream>("gone", 32));
  const std::string kept_path = host.Add(std::make_unique<CountedStream>("kept"));
  const int gone_fd = OpenRaw(gone_path);
  const int kept_fd = OpenRaw(kept_path);
  ASSERT_GE(gone_fd, 0);
  ASSERT_GE(kept_fd, 0);
  host.Start();
  const std::unique_ptr<hil::RigPortCounter> counter = rig.Counter(kept_path);
  ASSERT_NE(counter, nullptr);
  ASSERT_TRUE(counter->Attach(5.0));
  ::tcflush(kept_fd, TCIFLUSH);  // as the unit link flushes after attaching

  SlowReader gone;
  gone.nap = std::chrono::milliseconds(0);
  std::thread gone_thread([&] { gone.Run(gone_fd); });
  CountedReader kept;
  kept.counter = counter.get();
  std::thread kept_thread([&] { kept.Run(kept_fd); });
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  gone.stop = true;  // the gone client keeps its port open and reads no more
  gone_thread.join();
  std::this_thread::sleep_for(std::chrono::duration<double>(kLockstepStallLimit_s - 0.5));
  kept.pause_ms = 2000;
  std::this_thread::sleep_for(std::chrono::milliseconds(3500));
  kept.stop = true;
  kept_thread.join();
  const bool still_attached = counter->attached();
  host.Stop();
  ::close(gone_fd);
  ::close(kept_fd);
  EXPECT_GT(host.held_wall_s(), 0.8 * kLockstepStallLimit_s) << "the gone client held nothing";
  EXPECT_GT(kept.reads.load(), 100u);
  EXPECT_TRUE(still_attached) << "the rig released a reader that was only waiting";
  EXPECT_LE(kept.worst_lag.load(), hil::kLockstepPacketBudget + kLockstepCheckFrames);
}

// A reader that attaches while the rig runs (its unit has sent far more than the packet budget)
// starts from the rig's count at the acknowledgement: a start taken before (the count when it
// asked, or none) would leave it lagging by all the rig ran meanwhile, the clock held for that
// lag and its flushed line bringing nothing, until the stall limit.
TEST(DeviceHostLockstep, AReaderAttachingToARunningRigStartsFromTheRigsCount) {
  CountingHost rig(100000.0);
  DeviceHost& host = rig.host;
  const std::string path = host.Add(std::make_unique<CountedStream>("late"));
  const int fd = OpenRaw(path);
  ASSERT_GE(fd, 0);
  host.Start();
  const std::unique_ptr<hil::RigPortCounter> counter = rig.Counter(path);
  ASSERT_NE(counter, nullptr);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (counter->Produced() < 4 * hil::kLockstepPacketBudget &&
         std::chrono::steady_clock::now() < deadline) {
    ReadFor(fd, 10);  // an earlier client of the port, not counted
  }
  ASSERT_GE(counter->Produced(), 4 * hil::kLockstepPacketBudget);
  ASSERT_TRUE(counter->Attach(5.0));
  EXPECT_GE(counter->Consumed(), 4 * hil::kLockstepPacketBudget);
  ::tcflush(fd, TCIFLUSH);
  CountedReader reader;
  reader.counter = counter.get();
  std::thread reader_thread([&] { reader.Run(fd); });
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  reader.stop = true;
  reader_thread.join();
  host.Stop();
  ::close(fd);
  EXPECT_GT(reader.reads.load(), 50u) << "the attached reader got nothing to read";
  EXPECT_LE(reader.worst_lag.load(), hil::kLockstepPacketBudget + kLockstepCheckFrames);
}

TEST(DeviceHostLockstep, ClockFileFollowsTheHost) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("adahrs-clock-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    DeviceHost host(100.0);
    host.SetClockFile(dir / "clock");
    host.Add(std::make_unique<FrameStream>());
    const hil::RigClock clock(dir / "clock");
    EXPECT_EQ(clock.time_scale(), 100.0);
    EXPECT_EQ(clock.NowS(), 0.0);
    host.Start();
    clock.SleepS(5.0);  // 50 ms wall at 100x
    const double rig_s = host.now_s();
    EXPECT_GE(clock.NowS(), 5.0);
    EXPECT_LE(clock.NowS(), rig_s + 1e-9);
    host.Stop();
    EXPECT_NEAR(clock.RigTimeS(), host.now_s(), 1e-9);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace adahrs::rig_sim
