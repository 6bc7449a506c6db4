// Rig throughput: 4 IMU + 1 ADS units streaming raw packets over their ptys to one reading client
// (tests/rig_sim/throughput_probe.h) for 1,800 simulated seconds at each requested time scale.
// Counters: achieved_x (simulated / wall seconds), lost (sequence gaps), bad (frames failing
// sync or CRC), host_lost (bytes the host could not hand to the ptys). The highest loss-free time
// scale is the largest requested scale with zero loss whose achieved_x keeps up with it; 100000
// asks for "as fast as the machine can".
#include <benchmark/benchmark.h>

#include "tests/rig_sim/throughput_probe.h"

namespace {

void BM_RigThroughput(benchmark::State& state) {
  const auto requested = static_cast<double>(state.range(0));
  adahrs::rig_sim::testing::ThroughputResult r;
  for (auto _ : state) r = adahrs::rig_sim::testing::MeasureThroughput(requested, 1800.0);
  state.counters["achieved_x"] = r.simulated_s / r.wall_s;
  state.counters["lost"] = static_cast<double>(r.lost);
  state.counters["bad"] = static_cast<double>(r.bad_frames);
  state.counters["host_lost"] = static_cast<double>(r.host_bytes_lost);
}
BENCHMARK(BM_RigThroughput)
    ->Arg(250)
    ->Arg(500)
    ->Arg(1000)
    ->Arg(2000)
    ->Arg(4000)
    ->Arg(100000)
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
