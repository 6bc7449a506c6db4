// The host in lockstep: a reader slower than the world holds the clock instead of losing bytes,
// a port nobody reads holds it only for kLockstepStallLimit_s, and the clock file follows.
#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "hil/rig_clock.h"
#include "rig_sim/device_host.h"

namespace adahrs::rig_sim {
namespace {

// A divisor of the host's lockstep writes (half the pty queue), so no record is torn when the
// host discards what it sent before a client read.
constexpr size_t kFrameBytes = 32;

// Sends one 32-byte record per world frame: the frame's index (u32, host order) and 28 bytes of
// its low byte, so a reader can tell a lost, repeated or torn record.
class FrameStream : public SerialDevice {
 public:
  const std::string& role() const override { return role_; }
  void Receive(std::span<const uint8_t>, double) override {}
  void Advance(double, double, RigEnvironment&) override { ++frame_; }
  void TakeOutput(double, std::vector<uint8_t>& out) override {
    uint8_t record[kFrameBytes];
    std::memcpy(record, &frame_, sizeof frame_);
    std::memset(record + sizeof frame_, static_cast<int>(frame_ & 0xff), kFrameBytes - sizeof frame_);
    out.insert(out.end(), record, record + kFrameBytes);
  }

 private:
  std::string role_ = "stream";
  uint32_t frame_ = 0;
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
  std::atomic<bool> stop{false};
  uint64_t records = 0;  // the last frame index read
  uint64_t read = 0;     // records read
  uint64_t out_of_order = 0;  // torn or going back
  uint64_t skipped = 0;       // records skipped
  void Run(int fd) {
    std::vector<uint8_t> pending;
    uint8_t buffer[512];
    while (!stop.load()) {
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
      if (n > 0) pending.insert(pending.end(), buffer, buffer + n);
      while (pending.size() >= kFrameBytes) {
        uint32_t frame = 0;
        std::memcpy(&frame, pending.data(), sizeof frame);
        const bool torn = pending[kFrameBytes - 1] != (frame & 0xff);
        if (torn || (read > 0 && frame <= records)) ++out_of_order;
        if (read > 0 && frame > records + 1) skipped += frame - records - 1;
        records = frame;
        ++read;
        pending.erase(pending.begin(), pending.begin() + kFrameBytes);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
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
  // What the host sent before it noticed the reader went unread (and, on a machine loaded enough
  // to stop the host itself for 0.5 s, what it discarded then): never silently.
  EXPECT_GE(host.bytes_lost(), reader.skipped * kFrameBytes);
  EXPECT_GT(reader.records, 1000u);
  // The world ran only as far as the reader read, plus what lockstep lets wait: the budget, the
  // pty's queue and one look's worth of frames.
  const double frames = host.now_s() / kWorldFrame_s;
  const double waiting =
      static_cast<double>(kLockstepBudgetBytes + kPtyQueueBytes) / kFrameBytes + kLockstepCheckFrames;
  EXPECT_LE(frames - static_cast<double>(reader.records), waiting);
  EXPECT_LT(frames, 0.5 * 2000.0 * 1.5 / kWorldFrame_s) << "the clock did not wait";
  EXPECT_GT(host.held_wall_s(), 0.5);
}

TEST(DeviceHostLockstep, PortNobodyOpensNeverHoldsTheClock) {
  DeviceHost host(1000.0);
  host.SetLockstep(true);
  host.Add(std::make_unique<FrameStream>());
  host.Start();
  // Longer than the rig's grace for bytes on their way into the queue, so writes age out of it.
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  host.Stop();
  EXPECT_GT(host.now_s(), 100.0);  // ~2500 s at 1000x; far past the budget's 4 s of this stream
  EXPECT_EQ(host.held_wall_s(), 0.0);
  EXPECT_GT(host.bytes_lost(), 0u);  // discarded as unread: nobody listens
}

TEST(DeviceHostLockstep, ClientThatLeavesHoldsTheClockForTheStallLimit) {
  DeviceHost host(1000.0);
  host.SetLockstep(true);
  const std::string path = host.Add(std::make_unique<FrameStream>());
  host.Start();
  const int fd = OpenRaw(path);
  ASSERT_GE(fd, 0);
  ::tcflush(fd, TCIFLUSH);  // the client takes over the line
  uint8_t buffer[4096];
  const auto read_until = std::chrono::steady_clock::now() + std::chrono::milliseconds(300);
  while (std::chrono::steady_clock::now() < read_until) {
    if (::read(fd, buffer, sizeof buffer) <= 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  ::close(fd);
  std::this_thread::sleep_for(std::chrono::duration<double>(kLockstepStallLimit_s * 0.5));
  const double held_s = host.now_s();
  std::this_thread::sleep_for(std::chrono::duration<double>(kLockstepStallLimit_s * 0.5 + 1.5));
  host.Stop();
  // Held at the budget (~5 s of this stream after the client left), then the port counts as
  // unread and the world runs on.
  EXPECT_GT(host.held_wall_s(), 0.5 * kLockstepStallLimit_s);
  EXPECT_GT(host.now_s(), held_s + 100.0);
}

TEST(DeviceHostLockstep, ClockFileFollowsTheHost) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("adahrs-clock-" + std::to_string(::getpid()));
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
