// adahrs diagnose on a 4-unit IMU calibration recording (target: the demo's ~11 M rows in <= 60 s
// on 2 cores): the shipped thermal (-40...+85 degC) and sensor calibration sequences recorded for
// four truth-profile units by the recording maker, the thermal profile compressed 60x (~0.2 M rows,
// the routine figure) or not at all (~11 M rows, minutes to make). Timed: reading both runs
// (streamed), cutting cells and row spectra, and the diagnosis of every unit.
#include <filesystem>
#include <string>

#include <benchmark/benchmark.h>

#include "common/gravity.h"
#include "diagnosis/diagnosis_output.h"
#include "tests/support/imu_recording_maker.h"

namespace adahrs::calib {
namespace {

std::filesystem::path Runs(int speedup) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("adahrs_diagnosis_benchmark_" + std::to_string(speedup));
  if (std::filesystem::exists(dir / "sensor" / "meta.json")) return dir;
  std::vector<sensor_sim::ImuUnitParams> params;
  for (int i = 0; i < 4; ++i) {
    params.push_back(sensor_sim::ImuUnitParams::Draw(
        "IMU-000" + std::to_string(i + 1), 60 + i, sensor_sim::ModelProfile::kTruth));
  }
  testing::MakerOptions options;
  options.thermal_speedup = speedup;
  testing::ImuRecordingMaker maker(params, common::NormalGravityMps2(32.6, 200.0), 9, options);
  maker.Run(testing::ShippedSequence("imu_thermal_calibration_full", 1000), dir / "thermal");
  maker.Run(testing::ShippedSequence("imu_sensor_calibration", 1000), dir / "sensor");
  return dir;
}

void BM_DiagnoseFourUnits(benchmark::State& state) {
  const std::filesystem::path dir = Runs(static_cast<int>(state.range(0)));
  const std::vector<std::filesystem::path> runs = {dir / "thermal", dir / "sensor"};
  int rows = 0;
  for (auto _ : state) {
    const diagnosis::DiagnosisRun run = diagnosis::DiagnoseRuns(runs, std::nullopt);
    rows = 0;
    for (const diagnosis::UnitDiagnosis& u : run.units) rows += u.rows;
    benchmark::DoNotOptimize(run);
  }
  state.counters["rows"] = rows;
  state.counters["rows_per_s"] =
      benchmark::Counter(rows, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_DiagnoseFourUnits)->Arg(60)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace adahrs::calib

BENCHMARK_MAIN();
