#include "sensor_sim/adxrs150.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/allan.h"
#include "tests/support/line_fit.h"

namespace adahrs::sensor_sim {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

constexpr double kFrame_s = 0.01;  // 100 Hz frames (reference-method.md)
// Independent scale from reference-method.md: 16 summed conversions · 2^19 codes / 5 V.
constexpr double kRateSumCountsPerV = 16.0 * 524288.0 / 5.0;
// 12-bit dsPIC ADC, 16 summed conversions, 0..5 V.
constexpr double kTempSumCountsPerV = 16.0 * 4096.0 / 5.0;

Adxrs150Effects NoEffects() {
  Adxrs150Effects e;
  e.noise = e.bias_instability = e.rate_random_walk = e.null_tempco = e.sensitivity_tempco =
      e.nonlinearity = e.g_sensitivity = e.supply_sensitivity = e.adc_quantization = false;
  return e;
}

Adxrs150Params TypicalWith(const Adxrs150Effects& effects) {
  Adxrs150Params p = Adxrs150Params::Typical();
  p.effects = effects;
  return p;
}

Adxrs150Input Still(double w_dps = 0.0, double temp_c = 25.0) {
  return Adxrs150Input{w_dps, 0.0, 0.0, 0.0, temp_c, 5.0};
}

// Mean rate counts over `frames` after `settle` frames at a constant input (the 40 Hz pole leaves
// 8 % of a step per frame: after 10 frames 1e-11 of it).
double MeanRate(Adxrs150& gyro, const Adxrs150Input& in, int frames, int settle = 10) {
  for (int i = 0; i < settle; ++i) gyro.Step(in);
  double sum = 0.0;
  for (int i = 0; i < frames; ++i) sum += gyro.Step(in).rate_cnt;
  return sum / frames;
}

std::vector<double> StaticRecordDps(const Adxrs150Params& p, uint64_t seed, size_t frames) {
  Adxrs150 gyro(p, seed, kFrame_s);
  std::vector<double> rate_dps(frames);
  for (double& r : rate_dps) r = gyro.Step(Still()).rate_cnt / gyro.RateCountsPerDps();
  return rate_dps;
}

// ---------------------------------------------------------------- scale, null, full scale

TEST(Adxrs150, TypicalCountsPerDpsIsTheThesisScale) {
  Adxrs150 gyro(TypicalWith(NoEffects()), 1, kFrame_s);
  const double expected_cnt_per_dps = kRateSumCountsPerV * 12.5e-3;  // = 20,971.52
  EXPECT_NEAR(gyro.RateCountsPerDps(), 20971.52, 1e-9);
  const double slope = (MeanRate(gyro, Still(100.0), 1) - MeanRate(gyro, Still(-100.0), 1)) / 200.0;
  // Requirement 0.01 % (2.1 counts/(deg/s)); the measurement resolves 1 count / 200 deg/s.
  EXPECT_NEAR(slope, expected_cnt_per_dps, 1e-4 * expected_cnt_per_dps);
  EXPECT_NEAR(MeanRate(gyro, Still(0.0), 1), 2.5 * kRateSumCountsPerV, 0.5);
  EXPECT_DOUBLE_EQ(gyro.NullCounts(), 2.5 * kRateSumCountsPerV);
}

TEST(Adxrs150, DrawnSensitivitiesStayInsideDatasheetLimits) {
  const double lo = kRateSumCountsPerV * 11.25e-3, hi = kRateSumCountsPerV * 13.75e-3;
  constexpr int kUnits = 300;
  double sum = 0.0, sum2 = 0.0;
  for (int seed = 1; seed <= kUnits; ++seed) {
    Adxrs150Params p = Adxrs150Params::Draw(seed);
    p.effects = NoEffects();
    Adxrs150 gyro(p, seed, kFrame_s);
    const double slope =
        (MeanRate(gyro, Still(100.0), 1) - MeanRate(gyro, Still(-100.0), 1)) / 200.0;
    EXPECT_GE(slope, lo - 0.01) << "seed " << seed;
    EXPECT_LE(slope, hi + 0.01) << "seed " << seed;
    const double ratio = slope / (kRateSumCountsPerV * 12.5e-3);
    sum += ratio;
    sum2 += ratio * ratio;
  }
  // +-10 % is drawn as 3 sigma (truncated): sigma 3.33 %; the truncation lowers it by ~1.5 %. The
  // sample std of 300 units has a ~4 % relative standard error, so [3.0, 3.6] % is a > 3-sigma
  // band.
  const double mean = sum / kUnits;
  const double std_pct = 100.0 * std::sqrt(sum2 / kUnits - mean * mean);
  EXPECT_NEAR(mean, 1.0, 0.01);
  EXPECT_GT(std_pct, 3.0);
  EXPECT_LT(std_pct, 3.6);
}

// reference-method.md Table 17: about +-3.1..3.2e6 counts at +-150 deg/s after removing the null.
TEST(Adxrs150, FullScaleCountsMatchReferenceTable17) {
  Adxrs150Effects e = Adxrs150Effects::Nominal();
  e.noise = e.bias_instability = false;
  Adxrs150 gyro(TypicalWith(e), 1, kFrame_s);
  const double null_cnt = MeanRate(gyro, Still(0.0), 1);
  for (double w_dps : {150.0, -150.0}) {
    const double span_cnt = std::fabs(MeanRate(gyro, Still(w_dps), 1) - null_cnt);
    EXPECT_GT(span_cnt, 3.1e6) << w_dps;
    EXPECT_LT(span_cnt, 3.2e6) << w_dps;
  }
}

TEST(Adxrs150, OutputClipsAtTheAdcRails) {
  Adxrs150 gyro(TypicalWith(NoEffects()), 1, kFrame_s);
  EXPECT_EQ(MeanRate(gyro, Still(400.0), 1), 16.0 * (524288 - 1));
  EXPECT_EQ(MeanRate(gyro, Still(-400.0), 1), 0.0);
}

// ---------------------------------------------------------------- nonlinearity

// Max deviation from the least-squares line over +-150 deg/s, in % of 150 deg/s.
double MeasuredNonlinearityPctFs(double quadratic_pct_fs, double cubic_pct_fs, bool on) {
  Adxrs150Effects e = NoEffects();
  e.nonlinearity = on;
  Adxrs150Params p = TypicalWith(e);
  p.nonlinearity_quadratic_pct_fs = quadratic_pct_fs;
  p.nonlinearity_cubic_pct_fs = cubic_pct_fs;
  Adxrs150 gyro(p, 1, kFrame_s);
  std::vector<double> w, c;
  for (int i = -1500; i <= 1500; ++i) {
    w.push_back(i * 0.1);
    c.push_back(MeanRate(gyro, Still(w.back()), 1));
  }
  const auto [intercept, slope] = test_support::FitLine(w, c);
  double max_dev = 0.0;
  for (size_t i = 0; i < w.size(); ++i) {
    max_dev = std::max(max_dev, std::fabs(c[i] - (intercept + slope * w[i])));
  }
  return 100.0 * max_dev / (slope * 150.0);
}

TEST(Adxrs150, NonlinearityIsTheConfiguredPercentOfFullScale) {
  struct Case {
    double quadratic, cubic, expected;
  };
  // Datasheet 0.1 % FS (R) in several shapes, and a larger value.
  for (const Case& k : {Case{0.1, 0.0, 0.1},
                        Case{0.0, -0.1, 0.1},
                        Case{0.06, -0.04, 0.1},
                        Case{-0.03, 0.05, 0.08},
                        Case{0.2, 0.3, 0.5}}) {
    // A 3001-point grid moves the discrete best-fit line from the continuous one by < 0.1 % of
    // the deviation; the 1-count rounding is 3e-5 % FS. Tolerance 1 % of the value.
    EXPECT_NEAR(
        MeasuredNonlinearityPctFs(k.quadratic, k.cubic, true), k.expected, 0.01 * k.expected)
        << k.quadratic << " " << k.cubic;
  }
  // Off: straight to the 1-count rounding (1 count = 3.2e-5 % FS).
  EXPECT_LT(MeasuredNonlinearityPctFs(0.2, 0.3, false), 1e-4);
}

// ---------------------------------------------------------------- noise

// Datasheet 0.05 deg/s/sqrt(Hz) (V, one-sided). Allan deviation N/sqrt(2 tau) (allan.h).
TEST(Adxrs150, WhiteRateNoiseMatchesDatasheetDensity) {
  Adxrs150Effects e = NoEffects();
  e.noise = e.adc_quantization = true;
  const std::vector<double> rate_dps = StaticRecordDps(TypicalWith(e), 42, 360000);  // 1 h
  constexpr double kDensity = 0.05;
  for (size_t m : {20u, 100u, 500u}) {  // 0.2, 1, 5 s: white region (filter pole at 4 ms)
    const common::AllanPoint p = common::OverlappingAllanDeviationAt(rate_dps, kFrame_s, m);
    // Requirement 10 %; statistical 1-sigma at 5 s is 2.6 %.
    EXPECT_NEAR(
        p.adev, kDensity / std::sqrt(2.0 * p.tau_s), 0.10 * kDensity / std::sqrt(2.0 * p.tau_s))
        << "tau " << p.tau_s;
  }
  // One-sided low-frequency PSD of the per-frame rate = density^2 (filter and frame averaging have
  // unit DC gain; aliasing adds < 0.3 %). Below 2 Hz the 40 Hz pole and the 10 ms average take
  // < 0.4 %. Welch over 175 segments x 82 bins: ~1 % standard error. Requirement 10 %.
  EXPECT_NEAR(common::LowFrequencyPsd(rate_dps, kFrame_s, 4096, 2.0),
              kDensity * kDensity,
              0.10 * kDensity * kDensity);
}

TEST(Adxrs150, BiasInstabilityFloorHasConfiguredMagnitude) {
  Adxrs150Effects e = NoEffects();
  e.noise = e.adc_quantization = e.bias_instability = true;
  Adxrs150Params p = TypicalWith(e);
  constexpr double kDensity = 0.05;
  const double floor_dps = p.bias_instability_dph / 3600.0;       // 75 deg/h (E)
  const std::vector<double> on = StaticRecordDps(p, 7, 3000000);  // 8.3 h
  p.effects.bias_instability = false;
  const std::vector<double> off = StaticRecordDps(p, 7, 3000000);
  for (size_t m : {3000u, 10000u, 30000u}) {  // 30, 100, 300 s
    const common::AllanPoint with = common::OverlappingAllanDeviationAt(on, kFrame_s, m);
    const double white_dps = kDensity / std::sqrt(2.0 * with.tau_s);
    // Expected: the floor and the white part in quadrature. Tolerance 15 %: the floor's +-4 %
    // ripple (gyro_bias_process.h) plus the estimator's scatter for flicker noise with 100..1000
    // clusters (seeds 7, 8, 9 measured within 7 % at 10..1000 s).
    const double expected = std::hypot(floor_dps, white_dps);
    EXPECT_NEAR(with.adev, expected, 0.15 * expected) << "tau " << with.tau_s;
    // Without it only white noise remains, 4..10x below the floor.
    const common::AllanPoint without = common::OverlappingAllanDeviationAt(off, kFrame_s, m);
    EXPECT_NEAR(without.adev, white_dps, 0.25 * white_dps) << "tau " << with.tau_s;
  }
}

TEST(Adxrs150, RateRandomWalkGrowsAsSqrtTauOverThree) {
  Adxrs150Effects e = NoEffects();
  e.rate_random_walk = true;
  Adxrs150Params p = TypicalWith(e);
  p.rate_random_walk_dph_per_rth = 600.0;  // large, so 1-count rounding is negligible
  const double k_dps_per_rts = 600.0 / 3600.0 / 60.0;
  const std::vector<double> rate_dps = StaticRecordDps(p, 3, 1000000);  // 10^4 s
  for (size_t m : {1000u, 10000u}) {                                    // 10, 100 s
    const common::AllanPoint a = common::OverlappingAllanDeviationAt(rate_dps, kFrame_s, m);
    const double expected = k_dps_per_rts * std::sqrt(a.tau_s / 3.0);
    // Random-walk Allan estimates scatter more than white ones; 100 clusters: ~15 % 1-sigma.
    EXPECT_NEAR(a.adev, expected, 0.35 * expected) << "tau " << a.tau_s;
  }
}

// ---------------------------------------------------------------- g, temperature, supply, filter

TEST(Adxrs150, FlippingGravityChangesMeanByTwiceGSensitivity) {
  Adxrs150Effects e = NoEffects();
  e.g_sensitivity = true;
  Adxrs150 gyro(TypicalWith(e), 1, kFrame_s);  // 0.2 deg/s/g on each axis (R)
  for (int axis = 0; axis < 3; ++axis) {
    Adxrs150Input up = Still(), down = Still();
    (axis == 0 ? up.f_x_g : axis == 1 ? up.f_y_g : up.f_z_g) = 1.0;
    (axis == 0 ? down.f_x_g : axis == 1 ? down.f_y_g : down.f_z_g) = -1.0;
    const double delta_dps =
        (MeanRate(gyro, up, 1) - MeanRate(gyro, down, 1)) / gyro.RateCountsPerDps();
    EXPECT_NEAR(delta_dps, 2.0 * 0.2, 1.0 / 20971.52) << "axis " << axis;  // 1 count
  }
}

TEST(Adxrs150, TempCountsFollowTheTempPinTransfer) {
  Adxrs150 gyro(TypicalWith(NoEffects()), 1, kFrame_s);
  // 2.50 V at 298.15 K = 25 degC (R), 8.4 mV/K (R): 32768 counts and 110.10 counts/degC.
  EXPECT_NEAR(gyro.Step(Still(0.0, 25.0)).temp_cnt, 2.5 * kTempSumCountsPerV, 0.5);
  const double c_hot = gyro.Step(Still(0.0, 85.0)).temp_cnt;
  const double c_cold = gyro.Step(Still(0.0, -40.0)).temp_cnt;
  EXPECT_NEAR((c_hot - c_cold) / 125.0, 8.4e-3 * kTempSumCountsPerV, 1.0 / 125.0);

  // Nominal (noise and quantisation on): the mean over 1000 frames is unbiased; per-frame
  // sigma ~2.3 counts (0.5 LSB ADC noise + quantisation on 16 conversions), so 0.3 counts > 4
  // sigma.
  Adxrs150 noisy(Adxrs150Params::Typical(), 9, kFrame_s);
  double sum = 0.0;
  for (int i = 0; i < 1000; ++i) sum += noisy.Step(Still(0.0, 25.0)).temp_cnt;
  EXPECT_NEAR(sum / 1000.0, 2.5 * kTempSumCountsPerV, 0.3);
}

TEST(Adxrs150, SupplyShiftsNullAbsoluteOrRatiometric) {
  Adxrs150Effects e = NoEffects();
  e.supply_sensitivity = true;
  Adxrs150Params p = TypicalWith(e);  // 1 deg/s/V (R)
  Adxrs150 absolute(p, 1, kFrame_s);
  const Adxrs150Input high{0.0, 0.0, 0.0, 0.0, 25.0, 5.25};
  EXPECT_NEAR(
      (MeanRate(absolute, high, 1) - MeanRate(absolute, Still(), 1)) / absolute.RateCountsPerDps(),
      0.25,
      1.0 / 20971.52);
  p.output_ratiometric = true;
  Adxrs150 ratiometric(p, 1, kFrame_s);
  // Null and offset scale with 5.25/5: (2.5 V + 12.5 mV · 0.25) · 1.05.
  EXPECT_NEAR(
      MeanRate(ratiometric, high, 1), (2.5 + 12.5e-3 * 0.25) * 1.05 * kRateSumCountsPerV, 0.5);
  EXPECT_NEAR(ratiometric.Step(high).temp_cnt, 2.5 * 1.05 * kTempSumCountsPerV, 0.5);
}

// A rate step through the R_OUT·C_OUT pole, sampled 16 times per frame at the end of each 1/16.
TEST(Adxrs150, OutputFilterStepResponseMatchesOnePole) {
  Adxrs150 gyro(TypicalWith(NoEffects()), 1, kFrame_s);
  const double tau_s = 180e3 * 22e-9;  // 3.96 ms, 40.2 Hz
  EXPECT_NEAR(gyro.OutputFilterCutoff_hz(), 40.19, 0.01);
  MeanRate(gyro, Still(0.0), 1);
  const double step_cnt = 100.0 * gyro.RateCountsPerDps();
  const double null_cnt = 2.5 * kRateSumCountsPerV;
  double lag_frame1 = 0.0;
  for (int j = 1; j <= 16; ++j) lag_frame1 += std::exp(-j * (kFrame_s / 16) / tau_s) / 16.0;
  const double lag_frame2 = lag_frame1 * std::exp(-kFrame_s / tau_s);
  EXPECT_NEAR(gyro.Step(Still(100.0)).rate_cnt, null_cnt + step_cnt * (1.0 - lag_frame1), 1.0);
  EXPECT_NEAR(gyro.Step(Still(100.0)).rate_cnt, null_cnt + step_cnt * (1.0 - lag_frame2), 1.0);
}

// ---------------------------------------------------------------- effect switches

struct EffectCase {
  const char* name;
  bool Adxrs150Effects::*flag;
  std::function<void(Adxrs150Params&)> perturb;  // changes only this effect's parameters
  Adxrs150Input input;
  double expected_delta_dps;  // NaN: stochastic, only "differs"
};

std::vector<EffectCase> EffectCases() {
  const double stochastic = std::nan("");
  return {
      {"null_tempco",
       &Adxrs150Effects::null_tempco,
       [](Adxrs150Params& p) {
         p.null_tc1_dps_per_c += 0.05;
         p.null_tc2_dps_per_c2 += 1e-4;
         p.null_tc3_dps_per_c3 += 1e-6;
       },
       Still(0.0, 65.0),
       0.05 * 40 + 1e-4 * 1600 + 1e-6 * 64000},
      {"sensitivity_tempco",
       &Adxrs150Effects::sensitivity_tempco,
       [](Adxrs150Params& p) {
         p.sensitivity_tc1_ppm_per_c += 200.0;
         p.sensitivity_tc2_ppm_per_c2 += 2.0;
       },
       Still(100.0, 65.0),
       100.0 * (200e-6 * 40 + 2e-6 * 1600)},
      {"nonlinearity",
       &Adxrs150Effects::nonlinearity,
       [](Adxrs150Params& p) { p.nonlinearity_quadratic_pct_fs += 0.1; },
       Still(150.0),
       0.1e-2 * 150.0},
      {"g_sensitivity",
       &Adxrs150Effects::g_sensitivity,
       [](Adxrs150Params& p) { p.g_sensitivity_dps_per_g[2] += 0.1; },
       Adxrs150Input{0.0, 0.0, 0.0, 1.0, 25.0, 5.0},
       0.1},
      {"supply_sensitivity",
       &Adxrs150Effects::supply_sensitivity,
       [](Adxrs150Params& p) { p.null_supply_dps_per_v += 1.0; },
       Adxrs150Input{0.0, 0.0, 0.0, 0.0, 25.0, 5.25},
       0.25},
      {"noise",
       &Adxrs150Effects::noise,
       [](Adxrs150Params& p) { p.rate_noise_dps_per_rthz *= 2; },
       Still(),
       stochastic},
      {"bias_instability",
       &Adxrs150Effects::bias_instability,
       [](Adxrs150Params& p) { p.bias_instability_dph *= 2; },
       Still(),
       stochastic},
      {"rate_random_walk",
       &Adxrs150Effects::rate_random_walk,
       [](Adxrs150Params& p) { p.rate_random_walk_dph_per_rth *= 2; },
       Still(),
       stochastic},
  };
}

std::vector<int32_t> Record(const Adxrs150Params& p, const Adxrs150Input& in, int frames) {
  Adxrs150 gyro(p, 77, kFrame_s);
  std::vector<int32_t> out(frames);
  for (int32_t& c : out) c = gyro.Step(in).rate_cnt;
  return out;
}

TEST(Adxrs150, EachEffectChangesOutputOnlyWhenOn) {
  constexpr int kFrames = 500;  // 5 s: long enough for the 1 s random-walk updates
  for (const EffectCase& k : EffectCases()) {
    Adxrs150Params base = Adxrs150Params::Typical();
    base.effects = Adxrs150Effects::All();
    // Zero the other terms that would multiply this one's output (nonlinearity shapes the rate
    // the sensitivity tempco scales), keeping each expected value a one-line formula.
    base.nonlinearity_quadratic_pct_fs = base.nonlinearity_cubic_pct_fs = 0.0;
    Adxrs150Params changed = base;
    k.perturb(changed);

    base.effects.*k.flag = false;
    changed.effects.*k.flag = false;
    EXPECT_EQ(Record(base, k.input, kFrames), Record(changed, k.input, kFrames))
        << k.name << ": its parameter matters while it is off";

    base.effects.*k.flag = true;
    changed.effects.*k.flag = true;
    const std::vector<int32_t> a = Record(base, k.input, kFrames);
    const std::vector<int32_t> b = Record(changed, k.input, kFrames);
    EXPECT_NE(a, b) << k.name << ": its parameter does not matter while it is on";
    if (!std::isnan(k.expected_delta_dps)) {
      // Same noise seed: the records differ by the deterministic term plus a +-1 count rounding.
      double delta = 0.0;
      for (int i = 0; i < kFrames; ++i) delta += b[i] - a[i];
      delta /= kFrames * 20971.52;
      EXPECT_NEAR(delta, k.expected_delta_dps, 1.0 / 20971.52) << k.name;
    }
  }
}

TEST(Adxrs150, QuantizationMakesNoiselessSumsMultiplesOfSixteen) {
  Adxrs150Effects e = NoEffects();
  e.adc_quantization = true;
  Adxrs150 quantized(TypicalWith(e), 1, kFrame_s);
  Adxrs150 ideal(TypicalWith(NoEffects()), 1, kFrame_s);
  int ideal_off_grid = 0;
  for (int i = 0; i < 100; ++i) {
    const Adxrs150Input in = Still(0.0137 * i, 20.0 + 0.37 * i);
    MeanRate(quantized, in, 1, 4);
    MeanRate(ideal, in, 1, 4);
    const Adxrs150Output q = quantized.Step(in), o = ideal.Step(in);
    EXPECT_EQ(q.rate_cnt % 16, 0);
    EXPECT_EQ(q.temp_cnt % 16, 0);
    EXPECT_LE(std::abs(q.rate_cnt - o.rate_cnt), 8);  // half an LSB of 16 counts
    ideal_off_grid += (o.rate_cnt % 16 != 0);
  }
  EXPECT_GT(ideal_off_grid, 50);
}

// ---------------------------------------------------------------- determinism and parameters

TEST(Adxrs150, DeterministicPerSeed) {
  Adxrs150Params p = Adxrs150Params::Draw(5);
  p.effects = Adxrs150Effects::All();
  const Adxrs150Input in{12.0, 0.1, -0.2, 0.97, 31.0, 5.05};
  EXPECT_EQ(Record(p, in, 300), Record(p, in, 300));
  Adxrs150 a(p, 1, kFrame_s), b(p, 2, kFrame_s);
  int same = 0;
  for (int i = 0; i < 100; ++i) same += a.Step(in).rate_cnt == b.Step(in).rate_cnt;
  EXPECT_LT(same, 5);
  EXPECT_EQ(Adxrs150Params::Draw(5).ToJson(), Adxrs150Params::Draw(5).ToJson());
  EXPECT_NE(Adxrs150Params::Draw(5).ToJson(), Adxrs150Params::Draw(6).ToJson());
}

TEST(Adxrs150, RefusesNonPositiveFramePeriod) {
  try {
    Adxrs150 gyro(Adxrs150Params::Typical(), 1, 0.0);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("frame_period_s"), HasSubstr("got 0")));
  }
}

TEST(Adxrs150, JsonRoundTripIsExact) {
  std::vector<Adxrs150Params> units = {Adxrs150Params::Typical()};
  for (uint64_t seed = 1; seed <= 20; ++seed) units.push_back(Adxrs150Params::Draw(seed));
  units.back().effects = Adxrs150Effects::All();
  units.back().output_ratiometric = true;
  for (const Adxrs150Params& p : units) {
    const nlohmann::json j = p.ToJson();
    // Through text, as a file would carry it.
    const nlohmann::json reparsed = nlohmann::json::parse(j.dump());
    const Adxrs150Params q = Adxrs150Params::FromJson(common::ParamReader(reparsed, "unit.json"));
    EXPECT_EQ(q, p);
    EXPECT_EQ(q.ToJson(), j);
  }
}

std::string FromJsonError(const nlohmann::json& j) {
  try {
    Adxrs150Params::FromJson(common::ParamReader(j, "gyro_x.json"));
  } catch (const common::ParamError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Adxrs150, BadParameterFilesNameFilePathAndRange) {
  const nlohmann::json good = Adxrs150Params::Typical().ToJson();

  nlohmann::json missing = good;
  missing.erase("null_v");
  EXPECT_THAT(FromJsonError(missing),
              AllOf(HasSubstr("gyro_x.json"), HasSubstr("$.null_v"), HasSubstr("missing key")));

  nlohmann::json missing_effect = good;
  missing_effect["effects"].erase("g_sensitivity");
  EXPECT_THAT(FromJsonError(missing_effect), HasSubstr("$.effects.g_sensitivity"));

  nlohmann::json wrong_unit = good;
  wrong_unit["null_mv"] = 2500.0;
  EXPECT_THAT(FromJsonError(wrong_unit), AllOf(HasSubstr("$.null_mv"), HasSubstr("unknown key")));

  nlohmann::json out_of_range = good;
  out_of_range["sensitivity_mv_per_dps"] = 30.0;
  EXPECT_THAT(FromJsonError(out_of_range),
              AllOf(HasSubstr("$.sensitivity_mv_per_dps"),
                    HasSubstr("value 30 out of range"),
                    HasSubstr("[1, 20] mV/(deg/s)")));

  nlohmann::json nan_string = good;
  nan_string["bias_instability_dph"] = "NaN";
  EXPECT_THAT(FromJsonError(nan_string),
              AllOf(HasSubstr("$.bias_instability_dph"),
                    HasSubstr("expected a number"),
                    HasSubstr("[0, 3600] deg/h")));

  nlohmann::json short_array = good;
  short_array["g_sensitivity_dps_per_g"] = {0.2, 0.2};
  EXPECT_THAT(FromJsonError(short_array),
              AllOf(HasSubstr("$.g_sensitivity_dps_per_g"), HasSubstr("array of 3")));

  nlohmann::json bad_element = good;
  bad_element["g_sensitivity_dps_per_g"][1] = 5.0;
  EXPECT_THAT(FromJsonError(bad_element),
              AllOf(HasSubstr("$.g_sensitivity_dps_per_g[1]"), HasSubstr("[-2, 2] deg/s/g")));
}

}  // namespace
}  // namespace adahrs::sensor_sim
