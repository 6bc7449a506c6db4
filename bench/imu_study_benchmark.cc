// One unit of the IMU study that docs/performance.md quotes: the reference against the improved
// strategy (docs/examples/studies/imu_reference.json, imu_improved.json: the shipped
// imu_thermal_sensor_calibration sequence, truth-profile units), per iteration one unit drawn,
// run in process, fitted with both strategies and evaluated with both. The CPU time per iteration
// is the CPU time of one unit: units per minute of one core = 60 s / that (a study on T cores
// runs T units side by side).
#include <malloc.h>

#include <filesystem>

#include <benchmark/benchmark.h>

#include "adahrs_build_paths.h"
#include "proving/studies/imu_study.h"

namespace adahrs::calib {
namespace {

void BM_ImuStudyUnit(benchmark::State& state) {
  const std::filesystem::path examples =
      std::filesystem::path(ADAHRS_SOURCE_DIR) / "docs/examples/studies";
  const std::vector<proving::StudyDefinition> strategies = {
      proving::LoadStudyDefinition(examples / "imu_reference.json", ADAHRS_SEQUENCE_DIR),
      proving::LoadStudyDefinition(examples / "imu_improved.json", ADAHRS_SEQUENCE_DIR)};
  mallopt(M_MMAP_THRESHOLD, 512 << 20);  // as adahrs study does: large blocks stay for reuse
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  proving::StudySettings settings;
  settings.seed = 7;
  int index = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(proving::RunImuStudyUnit(strategies, settings, index++));
}
BENCHMARK(BM_ImuStudyUnit)->Unit(benchmark::kSecond)->Iterations(5);

}  // namespace
}  // namespace adahrs::calib

BENCHMARK_MAIN();
