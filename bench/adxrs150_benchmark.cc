// Cost of one ADXRS150 frame (Step), nominal and truth effect sets. Budget (sensor_api): an IMU
// frame (3 gyros + 6 accelerometer channels) at 5 million frames/s per core, i.e. a gyro Step of a
// few tens of nanoseconds.
#include <benchmark/benchmark.h>

#include "sensor_sim/adxrs150.h"

namespace adahrs::sensor_sim {
namespace {

void Run(benchmark::State& state, const Adxrs150Effects& effects) {
  Adxrs150Params params = Adxrs150Params::Typical();
  params.effects = effects;
  Adxrs150 gyro(params, 1, 0.01);
  Adxrs150Input input{10.0, 0.0, 0.0, 1.0, 30.0, 5.0};
  int64_t i = 0;
  for (auto _ : state) {
    input.w_dps = static_cast<double>(++i & 1023) * 0.1;
    benchmark::DoNotOptimize(gyro.Step(input));
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_Adxrs150StepNominal(benchmark::State& state) { Run(state, Adxrs150Effects::Nominal()); }
void BM_Adxrs150StepAll(benchmark::State& state) { Run(state, Adxrs150Effects::All()); }
BENCHMARK(BM_Adxrs150StepNominal);
BENCHMARK(BM_Adxrs150StepAll);

}  // namespace
}  // namespace adahrs::sensor_sim
BENCHMARK_MAIN();
