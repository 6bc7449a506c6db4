#include "rig_sim/device_host.h"

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include <gtest/gtest.h>

namespace adahrs::rig_sim {
namespace {

// A test device: answers each received line with its upper-case copy, stamped with the frame
// time it was received at, and counts frames.
class UpperCaseDevice : public SerialDevice {
 public:
  const std::string& role() const override { return role_; }
  void Receive(std::span<const uint8_t> bytes, double now_s) override {
    for (uint8_t b : bytes) {
      if (b == '\n') {
        out_ += line_ + "@" + std::to_string(static_cast<long>(std::lround(now_s * 100))) + "\n";
        line_.clear();
      } else {
        line_ += static_cast<char>(std::toupper(b));
      }
    }
  }
  void Advance(double, double dt_s, RigEnvironment& env) override {
    ++frames;
    env.table_rate_dps += dt_s;  // a visible effect on the shared world
  }
  void TakeOutput(double, std::vector<uint8_t>& out) override {
    out.insert(out.end(), out_.begin(), out_.end());
    out_.clear();
  }
  long frames = 0;

 private:
  std::string role_ = "upper";
  std::string line_, out_;
};

int OpenClient(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY);
  termios tio{};
  ::tcgetattr(fd, &tio);
  ::cfmakeraw(&tio);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 1;
  ::tcsetattr(fd, TCSANOW, &tio);
  return fd;
}

std::string ReadLine(int fd, std::chrono::milliseconds timeout) {
  std::string line;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  char c;
  while (std::chrono::steady_clock::now() < deadline) {
    if (::read(fd, &c, 1) == 1) {
      if (c == '\n') return line;
      line += c;
    }
  }
  return line + "<timeout>";
}

TEST(DeviceHost, ServesADeviceOnAPtyAndAnswersAClient) {
  DeviceHost host(1.0);
  const std::string path = host.Add(std::make_unique<UpperCaseDevice>());
  EXPECT_EQ(path.rfind("/dev/pts/", 0), 0u) << path;
  host.Start();
  const int fd = OpenClient(path);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::write(fd, "hello\n", 6), 6);
  const std::string reply = ReadLine(fd, std::chrono::milliseconds(2000));
  EXPECT_EQ(reply.substr(0, 6), "HELLO@") << reply;
  ::close(fd);
  host.Stop();
}

TEST(DeviceHost, SimulatedTimeRunsAtTheTimeScale) {
  DeviceHost host(200.0);
  host.Add(std::make_unique<UpperCaseDevice>());
  const auto start = std::chrono::steady_clock::now();  // before the host's clock starts
  host.Start();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  host.Stop();
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // 200x for ~0.5 s wall is ~100 s simulated. The host never runs ahead of the scaled clock; it
  // may fall behind on a loaded machine, and then it must say so.
  EXPECT_LE(host.now_s(), 200.0 * wall_s + 1.0);
  if (host.now_s() < 0.9 * 200.0 * 0.5) {
    EXPECT_GT(host.max_frames_behind(), 0u) << "fell behind without reporting it";
  }
  // Every frame advanced the device exactly once: the world's integral equals the clock.
  double frames = 0;
  host.Run([&](std::vector<SerialDevice*>& devices, RigEnvironment& env) {
    frames = static_cast<double>(static_cast<UpperCaseDevice*>(devices[0])->frames);
    EXPECT_NEAR(env.table_rate_dps, host.now_s(), 1e-6);
  });
  EXPECT_NEAR(frames * kWorldFrame_s, host.now_s(), 1e-9);
}

TEST(DeviceHost, RefusesAnUnusableTimeScale) {
  EXPECT_THROW(DeviceHost(0.0), std::invalid_argument);
}

}  // namespace
}  // namespace adahrs::rig_sim
