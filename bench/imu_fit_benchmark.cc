// All IMU fits of a full 4-unit calibration recording (budget <= 1 s): the shipped thermal
// (-40...+85 degC, compressed 60x) and sensor calibration sequences (1000 packets per acquisition)
// recorded for four nominal units by the recording maker, then timed: reading both runs, selecting
// the data, and the reference and joint strategies for every unit.
#include <filesystem>

#include <benchmark/benchmark.h>

#include "calib/imu_calibration/imu_strategy.h"
#include "common/gravity.h"
#include "hil/recording/recording_reader.h"
#include "tests/support/imu_recording_maker.h"

namespace adahrs::calib {
namespace {

// The recording maker for four nominal units with thermal ramps `thermal_speedup` times faster.
testing::ImuRecordingMaker FourUnitMaker(double thermal_speedup) {
  std::vector<sensor_sim::ImuUnitParams> params;
  for (int i = 0; i < 4; ++i) {
    params.push_back(sensor_sim::ImuUnitParams::Draw(
        "IMU-000" + std::to_string(i + 1), 40 + i, sensor_sim::ModelProfile::kNominal));
  }
  testing::MakerOptions options;
  options.thermal_speedup = thermal_speedup;
  return testing::ImuRecordingMaker(params, common::NormalGravityMps2(32.6, 200.0), 7, options);
}

const std::filesystem::path& Runs() {
  static const std::filesystem::path base = [] {
    const auto dir = std::filesystem::temp_directory_path() / "adahrs_imu_fit_benchmark";
    testing::ImuRecordingMaker maker = FourUnitMaker(60.0);
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
BENCHMARK_CAPTURE(BM_FitFourUnits, joint, ImuStrategy::JointFormat2())
    ->Unit(benchmark::kMillisecond);

// A recording of the demo's size: the shipped imu_thermal_sensor_calibration sequence (the demo's
// IMU calibration run: ramps over -40...+85 degC at real speed, then the six positions and rates
// at five temperatures) for four nominal units, stored gzip as the executor stores it. The fit
// reads the whole recording, as `adahrs fit` does on the demo's run.
const std::filesystem::path& DemoSizeRun() {
  static const std::filesystem::path run = [] {
    const auto dir = std::filesystem::temp_directory_path() / "adahrs_imu_fit_benchmark" / "demo";
    testing::ImuRecordingMaker maker = FourUnitMaker(1.0);
    maker.Run(testing::ShippedSequence("imu_thermal_sensor_calibration", 1000), dir);
    return dir;
  }();
  return run;
}

void BM_FitDemoSizeRecording(benchmark::State& state, const ImuStrategy& strategy) {
  const std::vector<std::filesystem::path> runs = {DemoSizeRun()};
  int64_t rows = 0;
  hil::RowSinks count;
  count.imu = [&rows](hil::ImuRecordRow&&, int) { ++rows; };
  hil::StreamRecording(DemoSizeRun(), count);
  for (auto _ : state) benchmark::DoNotOptimize(FitImuRuns(runs, strategy, "bench"));
  state.counters["rows"] = static_cast<double>(rows);
}
BENCHMARK_CAPTURE(BM_FitDemoSizeRecording, reference, ImuStrategy::Reference())
    ->Unit(benchmark::kSecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_FitDemoSizeRecording, joint, ImuStrategy::JointFormat2())
    ->Unit(benchmark::kSecond)
    ->Iterations(3);

}  // namespace
}  // namespace adahrs::calib

BENCHMARK_MAIN();
