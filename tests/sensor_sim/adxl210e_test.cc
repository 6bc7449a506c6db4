#include "sensor_sim/adxl210e.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/units.h"
#include "sensor_sim/duty_cycle_modulator.h"
#include "tests/support/line_fit.h"

namespace adahrs::sensor_sim {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

constexpr double kFrame_s = 0.01;                  // 100 Hz firmware frame
constexpr double kFcy_hz = 29.4912e6;              // 7.3728 MHz × 16 PLL / 4 (physics.md §1.3)
constexpr double kT2Typical_cnt = 1e-3 * kFcy_hz;  // 1 ms at 125 kΩ: 29 491.2 ticks
constexpr double kFrame_cnt = kFrame_s * kFcy_hz;  // 294 912 ticks

Adxl210eInput At(double f_x_g,
                 double f_y_g = 0.0,
                 double f_z_g = 0.0,
                 double temp_c = 25.0,
                 double supply_v = 5.0) {
  return {f_x_g, f_y_g, f_z_g, temp_c, supply_v};
}

double DutyOf(const Adxl210eCapture& c) { return static_cast<double>(c.t1_cnt) / c.t2_cnt; }

// Typical part with every effect off: only the ideal transfer function and edge timing remain.
Adxl210eParams Ideal() {
  Adxl210eParams p = Adxl210eParams::Typical();
  p.effects = {false, false, false, false, false, false, false, false, false, false};
  return p;
}

struct MeanReading {
  double duty_x = 0.0;
  double duty_y = 0.0;
  double t2_cnt = 0.0;
};

// Settles `settle` frames on `input`, then averages `frames` frames.
MeanReading Average(Adxl210e& chip, const Adxl210eInput& input, int frames, int settle = 10) {
  for (int i = 0; i < settle; ++i) chip.Step(input);
  MeanReading m;
  for (int i = 0; i < frames; ++i) {
    const Adxl210eOutput out = chip.Step(input);
    m.duty_x += DutyOf(out.x) / frames;
    m.duty_y += DutyOf(out.y) / frames;
    m.t2_cnt += static_cast<double>(out.x.t2_cnt) / frames;
  }
  return m;
}

MeanReading Average(const Adxl210eParams& p, const Adxl210eInput& input, int frames = 50) {
  Adxl210e chip(p, 1, kFrame_s);
  return Average(chip, input, frames);
}

std::vector<Adxl210eOutput> Record(const Adxl210eParams& p,
                                   const Adxl210eInput& input,
                                   int frames,
                                   uint64_t seed = 1) {
  Adxl210e chip(p, seed, kFrame_s);
  std::vector<Adxl210eOutput> out;
  for (int i = 0; i < frames; ++i) out.push_back(chip.Step(input));
  return out;
}

bool SameOutputs(const std::vector<Adxl210eOutput>& a, const std::vector<Adxl210eOutput>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const auto& u, const auto& v) {
    return u.x.t1_cnt == v.x.t1_cnt && u.x.t2_cnt == v.x.t2_cnt && u.y.t1_cnt == v.y.t1_cnt &&
           u.y.t2_cnt == v.y.t2_cnt;
  });
}

// One tick of T1 over T2 is the duty resolution of a single frame (physics.md §1.3: 0.85 mg at
// 29.4912 MHz and 1 ms). Averages over frames whose edge phase moves do better, never worse.
constexpr double kDutyTick_ratio = 1.0 / kT2Typical_cnt;

// ---------------------------------------------------------------- duty-cycle modulator timing

TEST(DutyCycleModulator, ReportsTheLastPeriodCompletedInsideEachFrame) {
  const double period_cnt = 29491.2;
  DutyCycleModulator dcm(kFrame_cnt, -1234.5, 0.25);
  double previous_end_cnt = -1234.5;
  for (int k = 0; k < 1000; ++k) {
    const DcmPeriod p = dcm.NextFrame(period_cnt, 0.0, 0.0, 0.0);
    const double end_cnt = p.start_cnt + p.length_cnt;
    EXPECT_GE(p.start_cnt, 0.0);
    EXPECT_LE(end_cnt, kFrame_cnt);
    EXPECT_GT(end_cnt + period_cnt, kFrame_cnt);  // the next period would not complete
    // Continuous phase: the reported start lies a whole number of periods after the last end.
    const double periods = (p.start_cnt + kFrame_cnt - previous_end_cnt) / period_cnt;
    EXPECT_NEAR(periods, std::round(periods), 1e-6);
    previous_end_cnt = end_cnt;
  }
}

TEST(DutyCycleModulator, CaptureFloorsEdgesAndWrapsAt16Bits) {
  // Edges at 0.3 + 0.5 = 0.8 and 0.3 + 10.6 = 10.9 ticks are captured as 0 and 10.
  EXPECT_EQ(CaptureIntervalCnt(0.3, 0.5, 10.6, true), 10);
  EXPECT_EQ(CaptureIntervalCnt(0.3, 0.5, 10.2, true), 10);                // 0.8 → 0, 10.5 → 10
  EXPECT_EQ(CaptureIntervalCnt(0.0, 0.5, 10.2, true), 10);                // 0.5 → 0, 10.2 → 10
  EXPECT_EQ(CaptureIntervalCnt(0.6, 0.5, 10.2, true), 9);                 // 1.1 → 1, 10.8 → 10
  EXPECT_EQ(CaptureIntervalCnt(0.6, 0.5, 10.2, false), 10);               // 9.7 rounds to 10
  EXPECT_EQ(CaptureIntervalCnt(0.0, 0.0, 70000.0, true), 70000 - 65536);  // modulo 2^16
}

TEST(DutyCycleModulator, RationalPeriodGivesALimitCycleIrrationalPeriodDithers) {
  // Edge phase on the tick grid over 2000 frames. T2 = k + 1/2 ticks with an integer frame length
  // can only put edges at two grid phases (a limit cycle, physics.md §6 row 14); a period with an
  // irrational fractional part visits the whole grid, so the mean capture converges to T2.
  auto phases = [](double period_cnt, double* mean_t2_cnt) {
    DutyCycleModulator dcm(kFrame_cnt, -100.0, 0.0);
    std::set<long> seen;
    double sum = 0.0;
    const int frames = 2000;
    for (int k = 0; k < frames; ++k) {
      const DcmPeriod p = dcm.NextFrame(period_cnt, 0.0, 0.0, 0.0);
      const double edge = p.grid_phase_cnt + p.start_cnt;
      seen.insert(std::lround(1e6 * (edge - std::floor(edge))));
      sum += CaptureIntervalCnt(p.grid_phase_cnt, p.start_cnt, p.start_cnt + p.length_cnt, true);
    }
    *mean_t2_cnt = sum / frames;
    return seen.size();
  };
  double mean_rational_cnt = 0.0;
  double mean_irrational_cnt = 0.0;
  EXPECT_LE(phases(29491.5, &mean_rational_cnt), 2u);
  const double irrational_cnt = 29491.0 + (std::sqrt(5.0) - 1.0) / 2.0;
  EXPECT_GT(phases(irrational_cnt, &mean_irrational_cnt), 1000u);
  // Equidistributed phases: the mean of the floored differences is the true period; 2000 frames
  // of a golden-ratio rotation leave a discrepancy well below 0.01 tick.
  EXPECT_NEAR(mean_irrational_cnt, irrational_cnt, 0.01);
}

// ---------------------------------------------------------------- datasheet transfer function

TEST(Adxl210e, DrawnUnitsZeroGAndSensitivityInsideDatasheetBounds) {
  // 200 drawn chips, truth model, 25 °C, 5 V. Bounds: 0 g duty 50 % ± 8 % (±2 g at 4 %/g, the
  // ADXL202E-like range of physics.md §1.1, R) and 3.2 … 4.8 %/g (R). Noise averaged over 40
  // frames is 0.3 mg, 1e-4 of the bounds' width.
  std::vector<double> zero_g;
  for (uint64_t seed = 0; seed < 200; ++seed) {
    const Adxl210eParams p = Adxl210eParams::Draw(1000 + seed);
    Adxl210e chip(p, seed, kFrame_s);
    const MeanReading zero = Average(chip, At(0.0, 0.0), 40);
    for (double d0 : {zero.duty_x, zero.duty_y}) {
      EXPECT_GE(d0, 0.42) << "seed " << seed;
      EXPECT_LE(d0, 0.58) << "seed " << seed;
      zero_g.push_back(d0);
    }
    // Sensitivity from ±1 g along one axis at a time (cross-axis then adds nothing to that axis).
    const MeanReading px = Average(chip, At(1.0, 0.0), 40);
    const MeanReading mx = Average(chip, At(-1.0, 0.0), 40);
    const MeanReading py = Average(chip, At(0.0, 1.0), 40);
    const MeanReading my = Average(chip, At(0.0, -1.0), 40);
    for (double s_pct : {50.0 * (px.duty_x - mx.duty_x), 50.0 * (py.duty_y - my.duty_y)}) {
      EXPECT_GE(s_pct, 3.2) << "seed " << seed;
      EXPECT_LE(s_pct, 4.8) << "seed " << seed;
    }
  }
  // The spread is real, not collapsed: a ±8 % tolerance at 3σ gives σ = 2.67 % (truncation at 3σ
  // lowers it by 1.3 %); 400 values estimate σ within ±3.5 % (1σ), so ±15 % is over 4σ.
  double mean = 0.0;
  for (double d : zero_g) mean += d / zero_g.size();
  double var = 0.0;
  for (double d : zero_g) var += (d - mean) * (d - mean) / (zero_g.size() - 1);
  EXPECT_NEAR(std::sqrt(var), 0.08 / 3.0, 0.15 * 0.08 / 3.0);
}

TEST(Adxl210e, SensitivityRecoveredFromPlusMinusOneAndTenG) {
  // Truth model without noise and jitter at 25 °C, 5 V: the symmetric difference cancels the
  // zero-g duty and the quadratic nonlinearity, leaving S = 4 %/g. Tolerance: one tick of T1 in
  // each of the two readings over 2·a g.
  Adxl210eParams p = Adxl210eParams::Typical();
  p.effects.noise = false;
  p.effects.t2_jitter = false;
  for (double a_g : {1.0, 10.0}) {
    const double up = Average(p, At(a_g, -a_g)).duty_x;
    const double down = Average(p, At(-a_g, a_g)).duty_x;
    EXPECT_NEAR((up - down) / (2.0 * a_g), 0.04, kDutyTick_ratio / a_g) << a_g << " g";
    const double up_y = Average(p, At(-a_g, a_g)).duty_y;
    const double down_y = Average(p, At(a_g, -a_g)).duty_y;
    EXPECT_NEAR((up_y - down_y) / (2.0 * a_g), 0.04, kDutyTick_ratio / a_g) << a_g << " g";
  }
}

TEST(Adxl210e, PeriodIsRsetOver125Megaohm) {
  // T2 = RSET/125 MΩ (physics.md §1.1, V). Without jitter each T2 capture is a difference of two
  // floored edges, so within one tick of T2·Fcy. These RSET values make T2·Fcy a multiple of
  // 1/625 tick, so the edges visit a 625-point phase lattice instead of locking to the frame, and
  // the mean over 2000 frames is within 0.05 tick of T2·Fcy.
  for (double rset_ohm : {101e3, 127e3, 163e3}) {
    Adxl210eParams p = Ideal();
    p.effects.capture_quantization = true;
    p.rset_ohm = rset_ohm;
    const double t2_cnt = rset_ohm / 125e6 * kFcy_hz;
    Adxl210e chip(p, 3, kFrame_s);
    double sum = 0.0;
    for (int k = 0; k < 2000; ++k) {
      const Adxl210eOutput out = chip.Step(At(0.0));
      EXPECT_LE(std::fabs(out.x.t2_cnt - t2_cnt), 1.0);
      sum += out.x.t2_cnt;
    }
    EXPECT_NEAR(sum / 2000, t2_cnt, 0.05) << rset_ohm << " ohm";
  }
}

TEST(Adxl210e, CountsPerGAreFourPercentOfFcyTimesT2) {
  // physics.md §1.3 (D): counts per g = 0.04·Fcy·T2 = 1179.6 at 29.4912 MHz and 1 ms.
  // The typical part's T2 is exactly Δ/10, so its edges are locked to the frame: every frame
  // reads the same floored T1, within one tick of the exact value.
  Adxl210eParams p = Ideal();
  p.effects.capture_quantization = true;
  auto mean_t1 = [&](double a_g) {
    Adxl210e chip(p, 5, kFrame_s);
    double sum = 0.0;
    for (int k = 0; k < 2000; ++k) sum += chip.Step(At(a_g)).x.t1_cnt;
    return sum / 2000;
  };
  EXPECT_NEAR(mean_t1(1.0) - mean_t1(0.0), 0.04 * kFcy_hz * 1e-3, 1.0);
  // With RSET = 127 kΩ the edges move over a 625-point lattice; the 2000-frame mean is within
  // 0.05 tick of 0.04·Fcy·T2 = 1198.52.
  p.rset_ohm = 127e3;
  EXPECT_NEAR(mean_t1(1.0) - mean_t1(0.0), 0.04 * kFcy_hz * 127e3 / 125e6, 0.05);
}

TEST(Adxl210e, NonlinearityIsTheConfiguredPercentOfFullScaleFromBestFitLine) {
  // Sweep ±10 g in 41 points, fit the least-squares line, take the largest residual. A pure
  // quadratic k2·a² on this grid deviates by k2·(FS² − mean(a²)); mean(a²) on the 41-point grid is
  // FS²·(42/120) instead of FS²/3, so the expected maximum is nl·FS·1.5·(1 − 0.35) = 0.975·nl·FS.
  // Tolerance 0.005 % FS = 0.5 mg: 50-frame averages with a moving grid phase quantise to ≪ 1 tick.
  for (double nl_pct : {0.2, -0.5}) {
    Adxl210eParams p = Ideal();
    p.effects.capture_quantization = true;
    p.effects.nonlinearity = true;
    p.x.nonlinearity_pct_fs = nl_pct;
    std::vector<double> a, d;
    for (int i = -20; i <= 20; ++i) {
      a.push_back(0.5 * i);
      d.push_back(Average(p, At(a.back())).duty_x);
    }
    const auto [offset, slope] = test_support::FitLine(a, d);
    double worst_g = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
      const double residual_g = (d[i] - offset - slope * a[i]) / slope;
      if (std::fabs(residual_g) > std::fabs(worst_g)) worst_g = residual_g;
    }
    const double worst_pct_fs = 100.0 * worst_g / 10.0;
    EXPECT_NEAR(worst_pct_fs, 0.975 * nl_pct, 0.005) << nl_pct;
  }
}

// ---------------------------------------------------------------- noise

struct NoiseStats {
  double rms_g;
  double allan_g;
};

// Static record of the X axis in g, with the Typical zero-g duty and sensitivity removed. Capture
// quantisation off: T1 is then the exact interval rounded, a white error of 1/12 tick².
NoiseStats MeasureNoise(double filter_c_f, int frames, int block) {
  Adxl210eParams p = Ideal();
  p.effects.noise = true;
  p.effects.filter = true;
  p.x.filter_c_f = filter_c_f;
  Adxl210e chip(p, 11, kFrame_s);
  std::vector<double> a_g(frames);
  for (int k = 0; k < frames; ++k) a_g[k] = (DutyOf(chip.Step(At(0.0)).x) - 0.5) / 0.04;
  double mean = 0.0, var = 0.0;
  for (double x : a_g) mean += x / frames;
  for (double x : a_g) var += (x - mean) * (x - mean) / (frames - 1);
  // Non-overlapping Allan variance at τ = block frames: ½·mean of squared successive block means.
  const int blocks = frames / block;
  std::vector<double> means(blocks, 0.0);
  for (int b = 0; b < blocks; ++b) {
    for (int i = 0; i < block; ++i) means[b] += a_g[b * block + i] / block;
  }
  double allan = 0.0;
  for (int b = 1; b < blocks; ++b)
    allan += 0.5 * std::pow(means[b] - means[b - 1], 2) / (blocks - 1);
  return {std::sqrt(var), std::sqrt(allan)};
}

// Rounding T1 to a tick: variance 1/12 tick², in g through 0.04·T2 ticks per g.
const double kQuantVar_g2 = 1.0 / 12.0 / std::pow(0.04 * kT2Typical_cnt, 2);
constexpr double kDensity_g_per_rthz = 200e-6;  // physics.md §1.1, V

TEST(Adxl210e, PerSampleNoiseRmsIsDensityTimesRootHalfPiBandwidth) {
  // physics.md §1.2: rms = N·√(π/2·f−3dB) with f−3dB = 1/(2π·32 kΩ·0.1 µF) = 49.7 Hz: 1.78 mg,
  // plus the rounding variance (0.24 mg rms). 200 000 nearly independent samples estimate the rms
  // within 0.16 % (1σ); tolerance 1 % is over 6σ.
  const double f3db_hz = 1.0 / (2.0 * common::kPi * 32e3 * 0.1e-6);
  const double expected_g =
      std::sqrt(std::pow(kDensity_g_per_rthz, 2) * common::kPi / 2.0 * f3db_hz + kQuantVar_g2);
  EXPECT_NEAR(MeasureNoise(0.1e-6, 200000, 100).rms_g, expected_g, 0.01 * expected_g);
}

TEST(Adxl210e, LowFrequencyNoiseMatchesDensity) {
  // A frame reports one point sample of the filtered noise, so the 100 Hz stream's one-sided PSD
  // at 0 Hz is the aliased sum Σ_k N²/(1 + (2π·k·τ/Δ)²) = N²·x·coth(x), x = Δ/(2τ), plus the white
  // rounding error 2Δ·q². The Allan deviation at τ_A ≫ τ is √(PSD(0)/(2τ_A)) (IEEE 952).
  //  - C = 1 µF (τ = 32 ms, 5 Hz): aliasing adds 0.8 %: the stream shows the datasheet's
  //    200 µg/√Hz; required within 10 % of N/√(2τ_A) as the datasheet figure (physics.md §1.1).
  //  - C = 0.1 µF (τ = 3.2 ms, 50 Hz): x = 1.56, the fold raises PSD(0) by 71 %.
  // Both against the exact value within 5 %: 1 000 000 frames in 200-frame blocks (2 s) give 5000
  // blocks, an Allan-variance SE of 2 %, i.e. 1 % in deviation, so 5 % is 5σ; the finite-block
  // bias for τ = 32 ms is Σk·φ^k/(L·Σφ^k) < 1 %.
  const double tau_a_s = 200 * kFrame_s;
  for (double c_f : {1e-6, 0.1e-6}) {
    const double tau_s = 32e3 * c_f;
    const double x = kFrame_s / (2.0 * tau_s);
    const double psd0 =
        std::pow(kDensity_g_per_rthz, 2) * x / std::tanh(x) + 2.0 * kFrame_s * kQuantVar_g2;
    const double expected_g = std::sqrt(psd0 / (2.0 * tau_a_s));
    const double measured_g = MeasureNoise(c_f, 1000000, 200).allan_g;
    EXPECT_NEAR(measured_g, expected_g, 0.05 * expected_g) << c_f << " F";
    if (c_f == 1e-6) {
      const double datasheet_g = kDensity_g_per_rthz / std::sqrt(2.0 * tau_a_s);
      EXPECT_NEAR(measured_g, datasheet_g, 0.10 * datasheet_g);
    }
  }
}

// ---------------------------------------------------------------- each effect, on and off

TEST(Adxl210e, EachEffectOffIgnoresItsParameters) {
  // With an effect off, changing the parameters only it uses must leave every capture unchanged.
  struct Case {
    const char* name;
    std::function<void(Adxl210eParams&)> mutate;
  };
  const std::vector<Case> cases = {
      {"zero_g_tempco",
       [](Adxl210eParams& p) {
         p.x.zero_g_tc1_mg_per_c = 5;
         p.y.zero_g_tc3_mg_per_c3 = 1e-3;
       }},
      {"sensitivity_tempco",
       [](Adxl210eParams& p) {
         p.x.sensitivity_tc1_ppm_per_c = 500;
         p.y.sensitivity_tc2_ppm_per_c2 = 3;
       }},
      {"nonlinearity",
       [](Adxl210eParams& p) {
         p.x.nonlinearity_pct_fs = 1.0;
         p.y.nonlinearity_pct_fs = -1.0;
       }},
      {"cross_axis",
       [](Adxl210eParams& p) {
         p.x.cross_z_ratio = 0.05;
         p.y.cross_other_ratio = 0.05;
         p.xy_nonorthogonality_deg = 0.5;
       }},
      {"supply_sensitivity",
       [](Adxl210eParams& p) {
         p.x.zero_g_supply_pct_per_v = 4;
         p.y.zero_g_supply_pct_per_v = -4;
       }},
      {"t2_tempco", [](Adxl210eParams& p) { p.t2_tc_ppm_per_c = 1000; }},
      {"t2_jitter", [](Adxl210eParams& p) { p.t2_jitter_ppm = 500; }},
      {"filter",
       [](Adxl210eParams& p) {
         p.x.filter_c_f = 1e-6;
         p.y.filter_r_ohm = 40e3;
       }},
      {"noise", [](Adxl210eParams& p) { p.x.noise_density_ug_per_rthz = 1000; }},
  };
  // A changing input (temperature, supply, a step) so that every term would show if active.
  auto run = [](const Adxl210eParams& p) {
    Adxl210e chip(p, 9, kFrame_s);
    std::vector<Adxl210eOutput> out;
    for (int k = 0; k < 60; ++k) {
      const double a = k < 30 ? 2.0 : -7.0;
      out.push_back(chip.Step(At(a, -a, 0.7 * a, -20.0 + k, 4.5 + 0.02 * k)));
    }
    return out;
  };
  for (const Case& c : cases) {
    const Adxl210eParams base = Ideal();
    Adxl210eParams changed = base;
    c.mutate(changed);
    EXPECT_TRUE(SameOutputs(run(base), run(changed))) << c.name;
  }
}

TEST(Adxl210e, ZeroGTempcoShiftsDutyByThePolynomial) {
  // b1 = 2 mg/°C, b2 = 0.01 mg/°C², b3 = 1e-4 mg/°C³ at ΔT = 40 °C: 80 + 16 + 6.4 = 102.4 mg,
  // i.e. 0.004096 duty at 4 %/g. Tolerance one tick of T1 (1.4 % of the shift).
  Adxl210eParams p = Ideal();
  p.effects.zero_g_tempco = true;
  p.x.zero_g_tc1_mg_per_c = 2.0;
  p.x.zero_g_tc2_mg_per_c2 = 0.01;
  p.x.zero_g_tc3_mg_per_c3 = 1e-4;
  const double shift = Average(p, At(0.0, 0.0, 0.0, 65.0)).duty_x - Average(p, At(0.0)).duty_x;
  EXPECT_NEAR(shift, 0.04 * 0.1024, kDutyTick_ratio);
}

TEST(Adxl210e, SensitivityTempcoScalesTheResponse) {
  // s1 = 100 ppm/°C, s2 = 1 ppm/°C², s3 = 0.01 ppm/°C³ at ΔT = 40 °C: 6240 ppm of 5 g at 4 %/g
  // = 0.001248 duty (0.078 g at 5 g); zero-g is unaffected. Tolerance one tick of T1.
  Adxl210eParams p = Ideal();
  p.effects.sensitivity_tempco = true;
  p.x.sensitivity_tc1_ppm_per_c = 100.0;
  p.x.sensitivity_tc2_ppm_per_c2 = 1.0;
  p.x.sensitivity_tc3_ppm_per_c3 = 0.01;
  const double hot = Average(p, At(5.0, 0.0, 0.0, 65.0)).duty_x;
  const double ref = Average(p, At(5.0)).duty_x;
  EXPECT_NEAR(hot - ref, 0.04 * 5.0 * 6240e-6, kDutyTick_ratio);
  EXPECT_NEAR(Average(p, At(0.0, 0.0, 0.0, 65.0)).duty_x, 0.5, kDutyTick_ratio);
}

TEST(Adxl210e, CrossAxisAddsTransverseAndNonOrthogonalTerms) {
  // X: 0.02·f_y − 0.01·f_z; Y: (0.015 + sin 0.5°)·f_x + 0.01·f_z. With f = (3, 2, −4) g:
  // X gains 0.08 g, Y gains 3·0.0237265 − 0.04 = 0.031180 g. Tolerance one tick of T1.
  Adxl210eParams p = Ideal();
  p.x.cross_other_ratio = 0.02;
  p.x.cross_z_ratio = -0.01;
  p.y.cross_other_ratio = 0.015;
  p.y.cross_z_ratio = 0.01;
  p.xy_nonorthogonality_deg = 0.5;
  const MeanReading off = Average(p, At(3.0, 2.0, -4.0));
  p.effects.cross_axis = true;
  const MeanReading on = Average(p, At(3.0, 2.0, -4.0));
  EXPECT_NEAR((on.duty_x - off.duty_x) / 0.04, 0.08, kDutyTick_ratio / 0.04);
  EXPECT_NEAR((on.duty_y - off.duty_y) / 0.04,
              3.0 * (0.015 + std::sin(common::DegToRad(0.5))) - 0.04,
              kDutyTick_ratio / 0.04);
}

TEST(Adxl210e, SupplyMovesZeroGDutyByOnePercentPerVolt) {
  // physics.md §6 row 13 (R): 1 %/V typical; at 4 V the duty drops by 0.01 (0.25 g at 4 %/g).
  Adxl210eParams p = Ideal();
  p.effects.supply_sensitivity = true;
  EXPECT_NEAR(Average(p, At(0.0, 0.0, 0.0, 25.0, 4.0)).duty_x - 0.5, -0.01, kDutyTick_ratio);
}

TEST(Adxl210e, NonlinearityAtFullScale) {
  // k2 = 1.5·0.2 %/10 g = 3e-4 /g: at 10 g the duty rises by S·k2·100 = 0.0012 over linear.
  Adxl210eParams p = Ideal();
  const double linear = Average(p, At(10.0)).duty_x;
  p.effects.nonlinearity = true;
  EXPECT_NEAR(Average(p, At(10.0)).duty_x - linear, 0.04 * 3e-4 * 100.0, kDutyTick_ratio);
}

TEST(Adxl210e, T2TempcoStretchesThePeriod) {
  // 300 ppm/°C over +40 °C: T2 × 1.012. Mean of 50 floored captures within 0.2 tick.
  Adxl210eParams p = Ideal();
  p.effects.t2_tempco = true;
  p.t2_tc_ppm_per_c = 300.0;
  EXPECT_NEAR(Average(p, At(0.0, 0.0, 0.0, 65.0)).t2_cnt, kT2Typical_cnt * 1.012, 0.2);
  // The duty is a ratio: it does not change with the period.
  EXPECT_NEAR(Average(p, At(2.0, 0.0, 0.0, 65.0)).duty_x, 0.58, kDutyTick_ratio);
}

TEST(Adxl210e, T2JitterHasTheConfiguredRms) {
  // 100 ppm of 29 491.2 ticks = 2.949 ticks rms per period, plus flooring both edges of a period
  // whose length is spread over many ticks (variance 1/6 tick²): expected 2.977 ticks. 20 000
  // frames estimate the rms within 0.5 % (1σ); tolerance 3 %. Without jitter the floored period
  // takes only two adjacent values.
  Adxl210eParams p = Ideal();
  p.effects.capture_quantization = true;
  p.t2_jitter_ppm = 100.0;
  auto t2_rms = [&](bool jitter) {
    p.effects.t2_jitter = jitter;
    Adxl210e chip(p, 21, kFrame_s);
    const int frames = 20000;
    std::vector<double> t2(frames);
    double mean = 0.0;
    for (int k = 0; k < frames; ++k) mean += (t2[k] = chip.Step(At(0.0)).x.t2_cnt) / frames;
    double var = 0.0;
    for (double t : t2) var += (t - mean) * (t - mean) / (frames - 1);
    return std::sqrt(var);
  };
  const double expected_cnt = std::sqrt(std::pow(100e-6 * kT2Typical_cnt, 2) + 1.0 / 6.0);
  EXPECT_NEAR(t2_rms(true), expected_cnt, 0.03 * expected_cnt);
  EXPECT_LT(t2_rms(false), 0.5);
}

TEST(Adxl210e, CaptureQuantizationFloorsEdgesOnTheMovingGrid) {
  // Off: the interval is rounded, T2 = round(29 963.0592) = 29 963 every frame (RSET 127 kΩ).
  // On: edges floored on a grid whose phase moves by (n·T2 − Δ) mod 1 per frame, so T2 reads
  // 29 963 or 29 964 and averages to T2·Fcy: the 625-point phase lattice is visited unevenly over
  // a finite run, so 0.05 tick as in PeriodIsRsetOver125Megaohm (measured: 0.012).
  Adxl210eParams p = Ideal();
  p.rset_ohm = 127e3;
  const double t2_cnt = 127e3 / 125e6 * kFcy_hz;
  for (const Adxl210eOutput& out : Record(p, At(0.0), 100)) EXPECT_EQ(out.x.t2_cnt, 29963);
  p.effects.capture_quantization = true;
  std::set<int> values;
  double sum = 0.0;
  for (const Adxl210eOutput& out : Record(p, At(0.0), 5000)) {
    values.insert(out.x.t2_cnt);
    sum += out.x.t2_cnt;
  }
  EXPECT_EQ(values, (std::set<int>{29963, 29964}));
  EXPECT_NEAR(sum / 5000, t2_cnt, 0.05);
}

TEST(Adxl210e, NominalPeriodLocksToTheFrameALimitCycle) {
  // T2 = 1 ms is exactly a tenth of the 10 ms frame (29 491.2 ticks × 10 = 294 912): the DCM is
  // phase-locked to the frames, so the quantisation error is the same every frame (the limit
  // cycle of period one of physics.md §6 row 14) and averaging frames does not remove it.
  Adxl210eParams p = Ideal();
  p.effects.capture_quantization = true;
  const auto out = Record(p, At(0.3), 200);
  for (const Adxl210eOutput& o : out) {
    EXPECT_EQ(o.x.t1_cnt, out[0].x.t1_cnt);
    EXPECT_EQ(o.x.t2_cnt, out[0].x.t2_cnt);
  }
}

TEST(Adxl210e, FilterLagsAStepByTheRcTimeConstant) {
  // C = 1 µF: τ = 32 ms. A step 0 → 5 g at a frame start is sampled at s = Δ − ε with ε ∈ [T2,
  // 2·T2) (the last complete period's rising edge), so the first frame reads 5·(1 − e^{−s/τ}) ∈
  // [5·(1 − e^{−8/32}), 5·(1 − e^{−9/32})] = [1.106, 1.225] g; the next frame 5·(1 −
  // e^{−(10+s)/τ}). Without the filter the first frame reads 5 g. Tolerance one tick (0.85 mg).
  Adxl210eParams p = Ideal();
  p.x.filter_c_f = 1e-6;
  const double tick_g = kDutyTick_ratio / 0.04;
  auto reading_g = [](const Adxl210eOutput& o) { return (DutyOf(o.x) - 0.5) / 0.04; };
  EXPECT_NEAR(reading_g(Record(p, At(5.0), 1).back()), 5.0, tick_g);
  p.effects.filter = true;
  Adxl210e chip(p, 4, kFrame_s);
  chip.Step(At(0.0));
  const double first_g = reading_g(chip.Step(At(5.0)));
  EXPECT_GE(first_g, 5.0 * (1.0 - std::exp(-8.0 / 32.0)) - tick_g);
  EXPECT_LE(first_g, 5.0 * (1.0 - std::exp(-9.0 / 32.0)) + tick_g);
  // The sample instant s follows from the first reading; the second is 10 ms later ± one T2.
  const double s_ms = -32.0 * std::log(1.0 - first_g / 5.0);
  const double second_g = reading_g(chip.Step(At(5.0)));
  EXPECT_GE(second_g, 5.0 * (1.0 - std::exp(-(s_ms + 9.0) / 32.0)) - tick_g);
  EXPECT_LE(second_g, 5.0 * (1.0 - std::exp(-(s_ms + 11.0) / 32.0)) + tick_g);
}

// ---------------------------------------------------------------- determinism and parameters

TEST(Adxl210e, DeterministicPerSeed) {
  const Adxl210eParams p = Adxl210eParams::Draw(77);
  const auto a = Record(p, At(0.3, -0.2, 0.9), 500, 5);
  EXPECT_TRUE(SameOutputs(a, Record(p, At(0.3, -0.2, 0.9), 500, 5)));
  EXPECT_FALSE(SameOutputs(a, Record(p, At(0.3, -0.2, 0.9), 500, 6)));
}

// StepEach interleaves the chips' stages; it must leave every chip exactly where Step leaves it.
// Five chips (more than one pass of StepEach), different parts, seeds and inputs, with the input
// moving every frame so that filter, noise, tempco and jitter all act.
TEST(Adxl210e, StepEachMatchesSteppingEachChipInTurn) {
  constexpr int kChips = 5;
  std::vector<Adxl210e> one_by_one, together;
  for (int k = 0; k < kChips; ++k) {
    const Adxl210eParams p = Adxl210eParams::Draw(300 + k);
    one_by_one.emplace_back(p, 40 + k, kFrame_s);
    together.emplace_back(p, 40 + k, kFrame_s);
  }
  for (int i = 0; i < 2000; ++i) {
    std::vector<Adxl210eInput> inputs;
    for (int k = 0; k < kChips; ++k) {
      inputs.push_back(At(std::sin(1e-2 * i + k),
                          0.5 * std::cos(3e-3 * i) - 0.1 * k,
                          0.9 + 0.01 * k,
                          25.0 + 40.0 * std::sin(1e-3 * i),
                          5.0 + 0.01 * k));
    }
    std::vector<Adxl210eOutput> expected;
    for (int k = 0; k < kChips; ++k) expected.push_back(one_by_one[k].Step(inputs[k]));
    std::vector<Adxl210eOutput> got(kChips);
    Adxl210e::StepEach(together, inputs, got);
    ASSERT_TRUE(SameOutputs(got, expected)) << "frame " << i;
  }
}

TEST(Adxl210e, JsonRoundTripAndStableDraw) {
  for (uint64_t seed : {0u, 1u, 99u}) {
    const Adxl210eParams p = Adxl210eParams::Draw(seed);
    EXPECT_EQ(Adxl210eParams::FromJson(common::ParamReader(p.ToJson(), "test")), p);
    EXPECT_EQ(p.ToJson().dump(), Adxl210eParams::Draw(seed).ToJson().dump());
  }
  EXPECT_NE(Adxl210eParams::Draw(1), Adxl210eParams::Draw(2));
  Adxl210eParams typical = Adxl210eParams::Typical();
  typical.effects = Adxl210eEffects::Nominal();
  EXPECT_EQ(Adxl210eParams::FromJson(common::ParamReader(typical.ToJson(), "test")), typical);
}

std::string ErrorOf(const nlohmann::json& j) {
  try {
    Adxl210eParams::FromJson(common::ParamReader(j, "chip.json", "$.accel[0]"));
  } catch (const common::ParamError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Adxl210e, BadParametersNamePathAndRange) {
  const nlohmann::json good = Adxl210eParams::Typical().ToJson();
  nlohmann::json missing = good;
  missing["x"].erase("filter_c_f");
  EXPECT_THAT(
      ErrorOf(missing),
      AllOf(HasSubstr("chip.json"), HasSubstr("$.accel[0].x.filter_c_f"), HasSubstr("missing")));
  nlohmann::json wrong_unit = good;
  wrong_unit["x"]["filter_c_uf"] = 0.1;
  EXPECT_THAT(ErrorOf(wrong_unit),
              AllOf(HasSubstr("$.accel[0].x.filter_c_uf"), HasSubstr("unknown key")));
  nlohmann::json out_of_range = good;
  out_of_range["rset_ohm"] = 2e6;
  EXPECT_THAT(ErrorOf(out_of_range),
              AllOf(HasSubstr("$.accel[0].rset_ohm"),
                    HasSubstr("out of range"),
                    HasSubstr("[62500, 1.25e+06] ohm")));
  nlohmann::json nan = good;
  nan["y"]["sensitivity_pct_per_g"] = "NaN";
  EXPECT_THAT(ErrorOf(nan),
              AllOf(HasSubstr("$.accel[0].y.sensitivity_pct_per_g"),
                    HasSubstr("expected a number"),
                    HasSubstr("[2, 6] %/g")));
  nlohmann::json effect = good;
  effect["effects"].erase("filter");
  EXPECT_THAT(ErrorOf(effect), HasSubstr("$.accel[0].effects.filter"));
}

TEST(Adxl210e, RejectsAPeriodThatDoesNotFitTheFrameOrTimer) {
  Adxl210eParams p = Adxl210eParams::Typical();
  p.rset_ohm = 1e6;  // 8 ms: does not fit twice in a 10 ms frame
  try {
    Adxl210e chip(p, 1, kFrame_s);
    FAIL() << "accepted T2 = 8 ms in a 10 ms frame";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("fit twice"), HasSubstr("t2_cnt = 235930")));
  }
  p.rset_ohm = 250e3;  // 2 ms = 58 982 ticks: fits 16 bits, but not with 25 % drift margin
  EXPECT_THROW(Adxl210e(p, 1, 0.1), std::invalid_argument);
}

}  // namespace
}  // namespace adahrs::sensor_sim
