// Throughput of the sensor physics: frames of a 4-IMU + 1-ADS batch with every effect on (the
// "truth" profile). One unit frame = one unit's full 100 Hz frame. Target: at least 5 million
// unit-frames per second per core, i.e. ≥ 10,000x real time for the batch.
#include <benchmark/benchmark.h>

#include <vector>

#include "common/random.h"
#include "sensor_sim/ads_unit.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::sensor_sim {
namespace {

constexpr double kStartC = 25.0;

ImuStimulus Stimulus(int64_t i) {
  ImuStimulus s;
  s.f_B_g = Eigen::Vector3d(0.01, -0.02, 1.0);
  s.w_B_dps = Eigen::Vector3d(0.0, 0.0, 100.0);
  s.air_temp_c = kStartC + 1e-4 * static_cast<double>(i % 100000);
  return s;
}

void BM_ImuUnitFrame(benchmark::State& state) {
  ImuUnit unit(ImuUnitParams::Draw("IMU-B", 1, ModelProfile::kTruth), 2, kStartC);
  int64_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(unit.Step(Stimulus(i++)));
  state.counters["unit_frames_per_s"] =
      benchmark::Counter(static_cast<double>(i), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ImuUnitFrame);

void BM_AdsUnitFrame(benchmark::State& state) {
  AdsUnit unit(AdsUnitParams::Draw("ADS-B", 1, ModelProfile::kTruth), 2, kStartC);
  AdsStimulus s;
  s.ps_pa = 69680.0;
  s.qc_pa = 1630.3;
  s.oat_c = kStartC;
  int64_t i = 0;
  for (auto _ : state) {
    s.air_temp_c = kStartC + 1e-4 * static_cast<double>(i++ % 100000);
    benchmark::DoNotOptimize(unit.Step(s));
  }
  state.counters["unit_frames_per_s"] =
      benchmark::Counter(static_cast<double>(i), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AdsUnitFrame);

void BM_Batch4Imu1Ads(benchmark::State& state) {
  std::vector<ImuUnit> imus;
  for (int k = 0; k < 4; ++k) {
    imus.emplace_back(
        ImuUnitParams::Draw(
            "IMU-" + std::to_string(k), common::Rng::Derive(7, k), ModelProfile::kTruth),
        k,
        kStartC);
  }
  AdsUnit ads(AdsUnitParams::Draw("ADS-1", 9, ModelProfile::kTruth), 9, kStartC);
  AdsStimulus a;
  a.ps_pa = 69680.0;
  a.qc_pa = 1630.3;
  a.oat_c = kStartC;
  int64_t i = 0;
  for (auto _ : state) {
    const ImuStimulus s = Stimulus(i);
    for (ImuUnit& u : imus) benchmark::DoNotOptimize(u.Step(s));
    a.air_temp_c = s.air_temp_c;
    benchmark::DoNotOptimize(ads.Step(a));
    ++i;
  }
  // 5 unit frames per batch frame; real time is 100 batch frames per second.
  state.counters["unit_frames_per_s"] =
      benchmark::Counter(5.0 * static_cast<double>(i), benchmark::Counter::kIsRate);
  state.counters["x_real_time"] =
      benchmark::Counter(static_cast<double>(i) / 100.0, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Batch4Imu1Ads);

}  // namespace
}  // namespace adahrs::sensor_sim

BENCHMARK_MAIN();
