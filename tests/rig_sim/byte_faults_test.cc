#include "rig_sim/byte_faults.h"

#include <bit>
#include <cmath>

#include <gtest/gtest.h>

namespace adahrs::rig_sim {
namespace {

// Emits bytes 0,1,2,… (mod 256), `per_frame` each frame, and records what it received.
class CountingDevice : public SerialDevice {
 public:
  explicit CountingDevice(size_t per_frame) : per_frame_(per_frame) {}
  const std::string& role() const override { return role_; }
  void Receive(std::span<const uint8_t> bytes, double) override {
    received.insert(received.end(), bytes.begin(), bytes.end());
  }
  void Advance(double, double, RigEnvironment&) override {}
  void TakeOutput(double, std::vector<uint8_t>& out) override {
    for (size_t i = 0; i < per_frame_; ++i) out.push_back(static_cast<uint8_t>(next_++));
  }
  std::vector<std::string> PhysicalFaults() const override { return {"stuck"}; }
  void SetPhysicalFault(const std::string& fault, bool on) override {
    if (fault != "stuck") SerialDevice::SetPhysicalFault(fault, on);
    stuck = on;
  }
  std::vector<uint8_t> received;
  bool stuck = false;

 private:
  std::string role_ = "counter";
  size_t per_frame_;
  size_t next_ = 0;
};

struct Wrapped {
  explicit Wrapped(uint64_t seed, size_t per_frame = 1000) {
    auto inner = std::make_unique<CountingDevice>(per_frame);
    device = inner.get();
    faults = std::make_unique<ByteFaultDevice>(std::move(inner), seed);
  }
  std::vector<uint8_t> Frames(int count) {
    std::vector<uint8_t> out;
    RigEnvironment env;
    for (int i = 0; i < count; ++i) {
      faults->Advance(0.01 * (i + 1), 0.01, env);
      faults->TakeOutput(0.01 * (i + 1), out);
    }
    return out;
  }
  CountingDevice* device;
  std::unique_ptr<ByteFaultDevice> faults;
};

TEST(ByteFaultDevice, PassesEverythingUnchangedWithNoFault) {
  Wrapped w(1);
  const std::vector<uint8_t> out = w.Frames(3);
  ASSERT_EQ(out.size(), 3000u);
  for (size_t i = 0; i < out.size(); ++i) EXPECT_EQ(out[i], static_cast<uint8_t>(i));
  const std::vector<uint8_t> request{1, 2, 3};
  w.faults->Receive(request, 0.0);
  EXPECT_EQ(w.device->received, request);
  EXPECT_EQ(w.faults->role(), "counter");
}

TEST(ByteFaultDevice, SilentStopsBothDirections) {
  Wrapped w(1);
  w.faults->SetSwitch("silent", true);
  EXPECT_TRUE(w.Frames(5).empty());
  const std::vector<uint8_t> request{1, 2, 3};
  w.faults->Receive(request, 0.0);
  EXPECT_TRUE(w.device->received.empty());
  EXPECT_EQ(w.faults->counters().bytes_silenced, 5003u);
  w.faults->SetSwitch("silent", false);
  EXPECT_EQ(w.Frames(1).size(), 1000u);
}

TEST(ByteFaultDevice, GarbageKeepsTheCountAndTimingButNotTheContent) {
  Wrapped w(7);
  w.faults->SetSwitch("garbage", true);
  const std::vector<uint8_t> out = w.Frames(10);
  ASSERT_EQ(out.size(), 10000u);
  // Random bytes match the true byte with probability 1/256: 39 expected of 10,000, σ = 6.2;
  // more than 100 would mean the output was not replaced.
  size_t same = 0;
  for (size_t i = 0; i < out.size(); ++i) same += out[i] == static_cast<uint8_t>(i);
  EXPECT_LT(same, 100u);
  const std::vector<uint8_t> request{1, 2, 3};
  w.faults->Receive(request, 0.0);
  EXPECT_EQ(w.device->received, request);  // the instrument still hears the client
}

TEST(ByteFaultDevice, DropRateLosesTheStatedFractionOfBytes) {
  Wrapped w(11);
  w.faults->SetRate("drop_rate", 0.1);
  const std::vector<uint8_t> out = w.Frames(200);  // 200,000 bytes
  // Binomial: 180,000 kept expected, σ = sqrt(n p (1 − p)) = 134; 5σ = 671.
  EXPECT_NEAR(static_cast<double>(out.size()), 180000.0, 671.0);
  EXPECT_EQ(out.size() + w.faults->counters().bytes_dropped, 200000u);
  // The kept bytes are unchanged and in order.
  for (size_t i = 1; i < out.size(); ++i) EXPECT_NE(out[i], out[i - 1]);
}

TEST(ByteFaultDevice, CorruptRateFlipsExactlyOneBitInTheStatedFraction) {
  Wrapped w(13);
  w.faults->SetRate("corrupt_rate", 0.01);
  const std::vector<uint8_t> out = w.Frames(100);  // 100,000 bytes
  ASSERT_EQ(out.size(), 100000u);
  size_t corrupted = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    const auto diff = static_cast<uint8_t>(out[i] ^ static_cast<uint8_t>(i));
    if (diff == 0) continue;
    ++corrupted;
    EXPECT_EQ(std::popcount(diff), 1);
  }
  // 1,000 expected, σ = 31.5; 5σ = 157.
  EXPECT_NEAR(static_cast<double>(corrupted), 1000.0, 157.0);
  EXPECT_EQ(corrupted, w.faults->counters().bytes_corrupted);
}

TEST(ByteFaultDevice, SameSeedSameFaultsWhateverTheFrameSlicing) {
  // The device→client stream is faulted byte by byte from its own random stream: 10 frames of
  // 1,000 bytes and 100 frames of 100 bytes give the same faulted stream.
  Wrapped a(99, 1000), b(99, 100);
  for (Wrapped* w : {&a, &b}) {
    w->faults->SetRate("drop_rate", 0.05);
    w->faults->SetRate("corrupt_rate", 0.05);
  }
  EXPECT_EQ(a.Frames(10), b.Frames(100));
  Wrapped c(100, 1000);
  c.faults->SetRate("drop_rate", 0.05);
  c.faults->SetRate("corrupt_rate", 0.05);
  EXPECT_NE(a.Frames(10), c.Frames(10));
}

TEST(ByteFaultDevice, RefusesUnknownFaultsAndRatesOutOfRangeNamingTheRole) {
  Wrapped w(1);
  try {
    w.faults->SetRate("drop_rate", 1.5);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "counter: drop_rate 1.500000 not in 0…1");
  }
  EXPECT_THROW(w.faults->SetSwitch("drop_rate", true), std::invalid_argument);
  EXPECT_THROW(w.faults->SetRate("silent", 0.1), std::invalid_argument);
  // Physical faults pass through to the device.
  w.faults->SetPhysicalFault("stuck", true);
  EXPECT_TRUE(w.device->stuck);
  EXPECT_EQ(w.faults->PhysicalFaults(), std::vector<std::string>{"stuck"});
  EXPECT_THROW(w.faults->SetPhysicalFault("melted", true), std::invalid_argument);
}

}  // namespace
}  // namespace adahrs::rig_sim
