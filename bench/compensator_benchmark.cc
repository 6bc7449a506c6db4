// Host nanoseconds per compensated frame of the fixed-point model (engine emulation included),
// IMU fully calibrated and ADS surface. Constants: an identity-like exported set built inline
// (the tests' realistic fixtures live under tests/). Machine: see docs/firmware-compensator.md.
#include <benchmark/benchmark.h>

#include "firmware_model/constants_exporter.h"
#include "firmware_model/unit_firmware.h"

namespace adahrs::firmware_model {
namespace {

ImuCalibrationConstants BenchImu() {
  ImuCalibrationConstants c;
  const double inv_scale_g_per_duty[6] = {-25.35, -25.08, 25.26, 25.93, 25.57, -25.71};
  for (int ch = 0; ch < 9; ++ch) {
    c.thermal[ch].temp_sensor = ch < 6 ? ch % 3 : ch - 6;
    c.thermal[ch].k = {ch < 6 ? 0.001 : 4.2e6, ch < 6 ? 1e-8 : 2.0, ch < 6 ? 1e-14 : 1e-6};
  }
  for (int ch = 0; ch < 6; ++ch) c.accel[ch] = {0.002, 1.0 / inv_scale_g_per_duty[ch]};
  for (int g = 0; g < 3; ++g) c.gyro[g] = {0.0, {0.01, 4.77e-5, 1e-14, 1e-20}};
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      c.ca_mps2_per_g[r][k] = r == k ? 9.80665 : 0.1;
      c.cg[r][k] = r == k ? 1.0 : 0.01;
    }
  }
  return c;
}

void BM_ImuFullyCalibratedFrame(benchmark::State& state) {
  const ImuConstants constants = ExportImuConstants(BenchImu()).constants;
  ImuRawFrame raw{};
  for (int ch = 0; ch < 6; ++ch) {
    raw.t1_cnt[ch] = static_cast<uint16_t>(30000 + 100 * ch);
    raw.t2_cnt[ch] = 60000;
  }
  for (int g = 0; g < 3; ++g) raw.gyro_cnt[g] = 4200000 + 100000 * g;
  for (uint16_t& t : raw.temp_cnt) t = 32768;
  ImuCompensatedFrame out{};
  for (auto _ : state) {
    DspEngine engine;
    ImuCompensate(&engine, constants, ImuCompensationMode::kFullyCalibrated, raw, &out);
    benchmark::DoNotOptimize(out);
  }
}
BENCHMARK(BM_ImuFullyCalibratedFrame);

void BM_AdsSurfaceFrame(benchmark::State& state) {
  AdsCalibrationConstants c;
  // With hysteresis terms and the bridge codes' linearisation, so that every frame runs the four
  // operators and both square roots (the input is constant, so after the first frame the
  // operators take the unchanged-input path; the sweep test's max cycles cover the moving path).
  // Coefficients in the reference's letters a + b x + c y + d x^2, placed at their powers (the
  // surface is the x^p y^q array, calibration_constants.h).
  auto letters = [](double a, double b, double c, double d) {
    SurfaceCoefficients k{};
    k[0][0] = a;
    k[1][0] = b;
    k[0][1] = c;
    k[2][0] = d;
    return k;
  };
  c.altitude_ft = {letters(1000.0, -0.2, 1e-4, 1e-9),
                   30000,
                   200000,
                   5e6,
                   8e6,
                   SurfaceLaw::kDirect,
                   {-2.0, 0.005, 3000.0, -3.0, 0.0075, 20.0, 6.5e6, {25.0, 5.7e-5, 1e-13, 0.0}},
                   {6.5e6, 1.5e-7}};
  c.airspeed_kt = {letters(30.0, 0.001, 0.0, -1e-9),
                   30000,
                   100000,
                   5e6,
                   8e6,
                   SurfaceLaw::kDirect,
                   {-0.1, 0.0003, 40.0, -0.2, 0.0005, 20.0, 6.5e6, {25.0, 5.7e-5, 1e-13, 0.0}},
                   {6.5e6, 1.5e-7}};
  const AdsConstants constants = ExportAdsConstants(c).constants;
  const AdsRawFrame raw{150000, 50000, 6700000, 6800000, 0};
  AdsCompensatedFrame out{};
  AdsHysteresisState hysteresis;
  AdsHysteresisReset(&hysteresis);
  for (auto _ : state) {
    DspEngine engine;
    AdsCompensate(&engine, constants, AdsCompensationMode::kSurface, raw, &hysteresis, &out);
    benchmark::DoNotOptimize(out);
  }
}
BENCHMARK(BM_AdsSurfaceFrame);

}  // namespace
}  // namespace adahrs::firmware_model

BENCHMARK_MAIN();
