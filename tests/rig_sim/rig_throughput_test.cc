// 4 IMU + 1 ADS stream over their ports to one reader. In lockstep the rig's clock waits for the
// reader, so ten simulated hours arrive complete however busy the machine is (the wall time is
// printed, not judged). Free-running, the rig keeps the wall clock and a reader that falls behind
// loses packets: that test finds the highest of a few time scales at which one simulated hour
// arrives without loss on this machine, now, and states it (the benchmark,
// bench/rig_throughput_benchmark.cc, measures it finely; docs/performance.md "Rig throughput").
// Runs alone (SERIAL in tests/CMakeLists.txt): each runs a rig flat out and a reader against it;
// beside other rigs of the suite (or each other) the free-running one measures the machine's load,
// not the rig.
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "tests/rig_sim/throughput_probe.h"

namespace adahrs::rig_sim {
namespace {

void ExpectEveryPacket(const testing::ThroughputResult& r, double simulated_s) {
  ASSERT_GE(r.simulated_s, simulated_s);
  ASSERT_EQ(r.packets.size(), 5u);
  for (size_t i = 0; i < r.packets.size(); ++i) {
    // One packet per 10 ms sample (the last sample's packet may still be on the line).
    EXPECT_GE(r.packets[i], static_cast<uint64_t>(simulated_s / kUnitSamplePeriod_s) - 1)
        << "port " << i;
  }
  EXPECT_EQ(r.lost, 0u);
  EXPECT_EQ(r.bad_frames, 0u);
  EXPECT_EQ(r.host_bytes_lost, 0u);
}

TEST(RigThroughput, FourImusAndOneAdsStreamTenSimulatedHoursWithoutLoss) {
  // Top speed 1000x, above the ~900x the frame thread sustains with all five streams here, so the
  // readers, not the cap, set the pace.
  constexpr double kTopScale = 1000.0;
#if defined(__SANITIZE_ADDRESS__)
  // Under ASan/UBSan the build checks memory and arithmetic, not speed: one simulated hour.
  constexpr double kSimulated_s = 3600.0;
#else
  constexpr double kSimulated_s = 36000.0;
#endif
  const testing::ThroughputResult r = testing::MeasureThroughput(kTopScale, kSimulated_s, true);
  ExpectEveryPacket(r, kSimulated_s);
  RecordProperty("wall_s", std::to_string(r.wall_s));
  std::printf("lockstep: %.0f h simulated in %.1f s wall (%.0fx), lost %llu\n",
              kSimulated_s / 3600.0,
              r.wall_s,
              r.simulated_s / r.wall_s,
              static_cast<unsigned long long>(r.lost));
}

TEST(RigThroughput, FreeRunningStatesItsLossFreeTimeScale) {
  constexpr double kSimulated_s = 3600.0;
  double loss_free_scale = 0.0;
  for (double scale : {800.0, 400.0, 200.0, 100.0, 50.0}) {
    const testing::ThroughputResult r = testing::MeasureThroughput(scale, kSimulated_s);
    std::printf("free-running at %gx: 1 h in %.1f s wall, lost %llu, host bytes lost %llu\n",
                scale,
                r.wall_s,
                static_cast<unsigned long long>(r.lost),
                static_cast<unsigned long long>(r.host_bytes_lost));
    EXPECT_EQ(r.bad_frames, 0u) << scale << "x";  // loss, never corruption
    if (r.lost == 0 && r.host_bytes_lost == 0 && r.bad_frames == 0) {
      loss_free_scale = scale;
      break;
    }
  }
  RecordProperty("loss_free_time_scale", std::to_string(loss_free_scale));
  std::printf("free-running: loss-free at %gx on this machine now\n", loss_free_scale);
  // 200x: half the lowest loaded figure measured (400x at load average 8, five builds beside,
  // docs/performance.md), a 24th of the idle machine's 4,800x; 800x held here beside two busy
  // loops and another build (2026-12-07). A data path that delivers a quarter of what it does now
  // loses packets at 200x and trips it. The figure itself is the benchmark's
  // (bench/rig_throughput_benchmark.cc); this floor only has to hold on a loaded machine.
#if defined(__SANITIZE_ADDRESS__)
  EXPECT_GE(loss_free_scale, 50.0);  // the sanitizers check memory, not speed
#else
  EXPECT_GE(loss_free_scale, 200.0);
#endif
}

}  // namespace
}  // namespace adahrs::rig_sim
