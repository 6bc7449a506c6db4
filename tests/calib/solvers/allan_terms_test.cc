#include "calib/solvers/allan_terms.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "common/random.h"
#include "sensor_sim/adxrs150.h"

namespace adahrs::calib {
namespace {

constexpr double kFrame_s = 0.01;

// Ten minutes at rest of a typical ADXRS150 with noise and ADC quantisation only (datasheet
// 0.05 deg/s/sqrt(Hz), one-sided; the model is held to it in tests/sensor_sim/adxrs150_test.cc),
// in deg/s.
std::vector<double> GyroAtRestDps(bool bias_instability, uint64_t seed, size_t frames) {
  sensor_sim::Adxrs150Params p = sensor_sim::Adxrs150Params::Typical();
  sensor_sim::Adxrs150Effects e;
  e.noise = e.adc_quantization = true;
  e.bias_instability = bias_instability;
  e.rate_random_walk = e.null_tempco = e.sensitivity_tempco = e.nonlinearity = e.g_sensitivity =
      e.supply_sensitivity = false;
  p.effects = e;
  sensor_sim::Adxrs150 gyro(p, seed, kFrame_s);
  std::vector<double> rate_dps(frames);
  for (double& r : rate_dps) {
    r = gyro.Step(sensor_sim::Adxrs150Input{0.0, 0.0, 0.0, 0.0, 25.0, 5.0}).rate_cnt /
        gyro.RateCountsPerDps();
  }
  return rate_dps;
}

TEST(AllanTerms, WhiteTermOfAGyroAtRestIsItsDatasheetDensity) {
  const AllanTerms t = ReadAllanTerms(GyroAtRestDps(false, 11, 60000), kFrame_s);
  EXPECT_DOUBLE_EQ(t.white_tau_s, 1.0);
  EXPECT_NEAR(t.record_s, 600.0, 1e-9);
  // sigma(1 s) from 600 s has a 1-sigma relative error of 1/sqrt(2 (600 - 1)) = 2.9 %: 10 %.
  EXPECT_NEAR(t.density_one_sided_per_rthz, 0.05, 0.005);
  EXPECT_NEAR(t.random_walk_per_rts, 0.05 / std::sqrt(2.0), 0.0036);
  // White noise alone keeps falling: the record shows no floor, B is only an upper bound.
  EXPECT_TRUE(t.minimum_at_longest_tau);
  EXPECT_NEAR(t.bias_instability_tau_s, t.curve.back().tau_s, 1e-12);
}

TEST(AllanTerms, ShortRecordIsReadAtItsLongestTau) {
  const AllanTerms t = ReadAllanTerms(GyroAtRestDps(false, 12, 500), kFrame_s);  // 5 s
  EXPECT_LT(t.white_tau_s, 1.0);
  EXPECT_DOUBLE_EQ(t.white_tau_s, t.curve.back().tau_s);
  // Still the white term (the 40 Hz pole is far below 0.5 s): 40 clusters, ~11 %; 30 %.
  EXPECT_NEAR(t.density_one_sided_per_rthz, 0.05, 0.015);
}

TEST(AllanTerms, BiasInstabilityFloorIsFoundWhereTheCurveTurnsUp) {
  // White noise plus a rate random walk: the curve falls, reaches its minimum and rises again.
  std::vector<double> x(200000);
  common::Rng rng(5);
  double walk = 0.0;
  for (double& v : x) {
    walk += 2e-4 * rng.Normal();
    v = 0.05 * rng.Normal() + walk;
  }
  const AllanTerms t = ReadAllanTerms(x, kFrame_s);
  EXPECT_FALSE(t.minimum_at_longest_tau);
  EXPECT_GT(t.bias_instability_tau_s, t.curve.front().tau_s);
  EXPECT_LT(t.bias_instability_tau_s, t.curve.back().tau_s);
  double lowest = t.curve.front().adev;
  for (const auto& p : t.curve) lowest = std::min(lowest, p.adev);
  EXPECT_DOUBLE_EQ(t.bias_instability, lowest / 0.664);
}

TEST(AllanTerms, RefusesTooShortARecordOrABadInterval) {
  EXPECT_THROW(ReadAllanTerms(std::vector<double>(19, 1.0), kFrame_s), std::invalid_argument);
  EXPECT_THROW(ReadAllanTerms(std::vector<double>(100, 1.0), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace adahrs::calib
