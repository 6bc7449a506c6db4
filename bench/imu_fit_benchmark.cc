// All IMU fits of a full 4-unit calibration recording (budget <= 1 s): the shipped thermal
// (-40...+85 degC, compressed 60x) and sensor calibration sequences (1000 packets per acquisition)
// recorded for four nominal units by the recording maker, then timed: reading both runs, selecting
// the data, and the reference and joint strategies for every unit.
#include <filesystem>

#include <benchmark/benchmark.h>

#include "calib/imu_calibration/imu_strategy.h"
#include "sensor_sim/gravity.h"
#include "tests/calib/imu_recording_maker.h"

namespace adahrs::calib {
namespace {

const std::filesystem::path& Runs() {
  static const std::filesystem::path base = [] {
    const auto dir = std::filesystem::temp_directory_path() / "adahrs_imu_fit_benchmark";
    std::vector<sensor_sim::ImuUnitParams> params;
    for (int i = 0; i < 4; ++i) {
      params.push_back(sensor_sim::ImuUnitParams::Draw(
          "IMU-000" + std::to_string(i + 1), 40 + i, sensor_sim::ModelProfile::kNominal));
    }
    testing::MakerOptions options;
    options.thermal_speedup = 60.0;
    testing::ImuRecordingMaker maker(
        params, sensor_sim::NormalGravityMps2(32.6, 200.0), 7, options);
    maker.Run(testing::ShippedSequence("imu_thermal_calibration_full", 1000), dir / "thermal");
    maker.Run(testing::ShippedSequence("imu_sensor_calibration", 1000), dir / "sensor");
    return dir;
  }();
  return base;
}

void BM_FitFourUnits(benchmark::State& state, const ImuStrategy& strategy) {
  const std::vector<std::filesystem::path> runs = {Runs() / "thermal", Runs() / "sensor"};
  for (auto _ : state) benchmark::DoNotOptimize(FitImuRuns(runs, strategy, "bench"));
}
BENCHMARK_CAPTURE(BM_FitFourUnits, reference, ImuStrategy::Reference())
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FitFourUnits, joint, ImuStrategy::Improved())->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace adahrs::calib

BENCHMARK_MAIN();
