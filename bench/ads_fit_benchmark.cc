// The reference ADS surface fit (calib/solvers/ads_surface_fit.h) over one million points, the
// issue-6 budget being <= 1 s. The points are a noiseless typical static bridge over the
// calibration envelope (-1,000...50,000 ft x -40...+85 degC), synthesised in closed form here so
// that only the fit is timed. Results: docs/performance.md.
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include "calib/solvers/ads_surface_fit.h"
#include "sensor_sim/atmosphere.h"
#include "sensor_sim/pressure_bridge.h"

namespace adahrs::calib {
namespace {

constexpr int kPoints = 1000000;
constexpr double kCodesPerVolt = 8388608.0 / 4.096;  // ADS1254 at VREF 4.096 V

std::vector<SurfaceSample> Samples() {
  const auto params =
      sensor_sim::PressureBridgeParams::Typical(sensor_sim::PressureBridgeKind::kAbsolute);
  std::vector<SurfaceSample> out;
  out.reserve(kPoints);
  constexpr int kTemps = 1000;
  for (int i = 0; i < kPoints; ++i) {
    const double temp_c = -40.0 + 125.0 * (i % kTemps) / (kTemps - 1);
    const double alt_ft = -1000.0 + 51000.0 * (i / kTemps) / (kPoints / kTemps - 1);
    sensor_sim::PressureBridge bridge(params, 0);
    const auto o = bridge.Step({sensor_sim::IsaStaticPressurePaFromFt(alt_ft), temp_c});
    out.push_back({o.signal_v * kCodesPerVolt, 0.5 * o.bridge_v * kCodesPerVolt, alt_ft, temp_c});
  }
  return out;
}

void BM_ReferenceSurfaceFitMillionPoints(benchmark::State& state) {
  const std::vector<SurfaceSample> samples = Samples();
  for (auto _ : state) {
    benchmark::DoNotOptimize(FitReferenceSurface("altitude surface", samples));
  }
  state.SetItemsProcessed(state.iterations() * kPoints);
}
BENCHMARK(BM_ReferenceSurfaceFitMillionPoints)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace adahrs::calib

BENCHMARK_MAIN();
