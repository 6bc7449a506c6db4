// One unit of the ADS study that docs/performance.md quotes: the reference against the improved
// strategy (docs/examples/studies/ads_reference.json, ads_improved.json: the shipped
// ads_calibration sequence, truth-profile units), per iteration one unit drawn, run in process,
// fitted with both strategies and evaluated with both. The CPU time per iteration is the CPU time
// of one unit: units per minute of one core = 60 s / that (a study on T cores runs T units side by
// side).
#include <filesystem>

#include <benchmark/benchmark.h>

#include "adahrs_build_paths.h"
#include "proving/studies/ads_study.h"

namespace adahrs::calib {
namespace {

void BM_AdsStudyUnit(benchmark::State& state) {
  const std::filesystem::path examples =
      std::filesystem::path(ADAHRS_SOURCE_DIR) / "docs/examples/studies";
  const std::vector<proving::StudyDefinition> strategies = {
      proving::LoadStudyDefinition(examples / "ads_reference.json", ADAHRS_SEQUENCE_DIR),
      proving::LoadStudyDefinition(examples / "ads_improved.json", ADAHRS_SEQUENCE_DIR)};
  proving::StudySettings settings;
  settings.seed = 7;
  int index = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(proving::RunAdsStudyUnit(strategies, settings, index++));
}
BENCHMARK(BM_AdsStudyUnit)->Unit(benchmark::kMillisecond)->Iterations(10);

}  // namespace
}  // namespace adahrs::calib

BENCHMARK_MAIN();
