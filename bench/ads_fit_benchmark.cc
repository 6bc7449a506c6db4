// The reference ADS surface fit (calib/solvers/ads_surface_fit.h) over one million points, its
// budget being <= 1 s. The points are a noiseless typical static bridge over the
// calibration envelope (-1,000...50,000 ft x -40...+85 degC), synthesised in closed form here so
// that only the fit is timed. And the whole pressure_minimax and hysteresis_compensated
// strategies (tolerance_ads_strategy.h: order selection by held-out temperatures, then two Lawson
// minimax fits per surface, or the linearisation, one least-squares fit with the history terms
// and the die-temperature cubic) on one unit's calibration points as the shipped ads_calibration
// sequence takes them (9 temperatures in its order, 13 altitudes, the 20,000 and 7,500 ft return
// points and 9 airspeeds each, sweeps alternating: 216 points), from a drawn unit with every
// effect on (the strategies replay the bridges' history from the points' order, timed with them).
// Results: docs/performance.md.
#include <algorithm>
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include "calib/ads_calibration/tolerance_ads_strategy.h"
#include "calib/solvers/ads_surface_fit.h"
#include "common/air_data.h"
#include "common/atmosphere.h"
#include "sensor_sim/ads_unit.h"
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
    const auto o = bridge.Step({common::IsaStaticPressurePaFromFt(alt_ft), temp_c});
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

std::vector<AdsCalibrationPoint> ShippedSequencePoints() {
  auto params = sensor_sim::AdsUnitParams::Draw("ADS-BENCH", 7, sensor_sim::ModelProfile::kTruth);
  params.static_thermal.effects.lag = false;  // every point a soak, as the sequence's are
  params.pitot_thermal.effects.lag = false;
  sensor_sim::AdsUnit unit(params, 1, 25.0);
  std::vector<double> alts_ft = {
      -1000, 0, 1000, 2000, 3500, 5000, 7500, 10000, 15000, 20000, 30000, 40000, 50000};
  std::vector<double> cas_kt = {30, 45, 60, 80, 100, 150, 250, 350, 450};
  std::vector<AdsCalibrationPoint> points;
  int step = 0;
  for (double temp_c : {-40.0, -15.0, 25.0, 65.0, 85.0, 75.0, 45.0, 0.0, -30.0}) {
    auto take = [&](double ps_pa, double qc_pa, bool airspeed) {
      sensor_sim::AdsRawFrame f{};
      for (int k = 0; k < 3; ++k) f = unit.Step({ps_pa, qc_pa, temp_c, temp_c});
      AdsCalibrationPoint p;
      p.step = step++;
      p.ps_cnt = f.ps_cnt;
      p.pt_cnt = f.pt_cnt;
      p.ps_temp_cnt = f.ps_temp_cnt;
      p.pt_temp_cnt = f.pt_temp_cnt;
      p.ps_ref_pa = ps_pa;
      p.qc_ref_pa = qc_pa;
      p.chamber_c = temp_c;
      p.airspeed_point = airspeed;
      points.push_back(p);
    };
    for (double alt_ft : alts_ft) take(common::IsaStaticPressurePaFromFt(alt_ft), 0.0, false);
    for (double alt_ft : {20000.0, 7500.0})
      take(common::IsaStaticPressurePaFromFt(alt_ft), 0.0, false);
    for (double kt : cas_kt) {
      take(common::kIsaSeaLevelPressure_pa, common::ImpactPressurePaFromKt(kt), true);
    }
    std::reverse(alts_ft.begin(), alts_ft.end());
    std::reverse(cas_kt.begin(), cas_kt.end());
  }
  return points;
}

void BM_StrategyOneUnit(benchmark::State& state, const char* strategy) {
  const std::vector<AdsCalibrationPoint> points = ShippedSequencePoints();
  for (auto _ : state) benchmark::DoNotOptimize(FitAdsStrategy(strategy, "ADS-BENCH", points));
}
BENCHMARK_CAPTURE(BM_StrategyOneUnit, pressure_minimax, kPressureAdsStrategyName)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);
BENCHMARK_CAPTURE(BM_StrategyOneUnit, hysteresis_compensated, kHysteresisAdsStrategyName)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

}  // namespace
}  // namespace adahrs::calib

BENCHMARK_MAIN();
