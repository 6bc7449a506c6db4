#include "sensor_sim/ads1254.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace adahrs::sensor_sim {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

Ads1254Params Ideal() {
  Ads1254Params p = Ads1254Params::Typical();
  p.effects = Ads1254Effects{};
  return p;
}

double RmsNoiseV(const Ads1254Params& p, double input_v, int samples, uint64_t seed) {
  Ads1254 adc(p, seed);
  double sum = 0.0;
  double sum2 = 0.0;
  for (int i = 0; i < samples; ++i) {
    const double v = adc.Convert(input_v) * adc.NominalLsbV();
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / samples;
  return std::sqrt(sum2 / samples - mean * mean);
}

TEST(Ads1254, NoiseMatchesDatasheetTableForAveraging) {
  // SBAS213 p.15 (physics.md §3.3, V): at VREF 4.096 V, 20 kHz: N = 1 → 14.6 µV rms,
  // N = 16 → 3.65 µV, N = 256 → 0.91 µV. Brief: within 10 %. With 20 000 samples the relative
  // standard error of an rms estimate is 1/√(2·20 000) = 0.5 %, so 10 % is > 20 sigma; the
  // quantisation (LSB 0.49 µV, LSB/√12 = 0.14 µV) adds ≤ 1.2 % at N = 256.
  struct Row {
    int n;
    double rms_uv;
  };
  for (const Row& row : {Row{1, 14.6}, Row{16, 3.65}, Row{256, 0.91}}) {
    Ads1254Params p = Ideal();
    p.effects.noise = true;
    p.averaging_count = row.n;
    EXPECT_NEAR(RmsNoiseV(p, 0.1, 20000, 7) * 1e6, row.rms_uv, 0.1 * row.rms_uv) << "N " << row.n;
  }
}

TEST(Ads1254, IdealTransferAndClipping) {
  // Two's complement, 2^23 codes per VREF; +VREF and beyond clip to 0x7FFFFF, −VREF and beyond
  // to 0x800000 (SBAS213 output coding).
  Ads1254 adc(Ideal(), 1);
  const double vref_v = 4.096;
  const double lsb_v = vref_v / 8388608.0;
  EXPECT_DOUBLE_EQ(adc.NominalLsbV(), lsb_v);
  EXPECT_EQ(adc.Convert(0.0), 0);
  EXPECT_EQ(adc.Convert(vref_v / 2.0), 4194304);
  EXPECT_EQ(adc.Convert(-vref_v / 4.0), -2097152);
  EXPECT_EQ(adc.Convert(1000.5 * lsb_v + 0.1 * lsb_v), 1001);
  EXPECT_EQ(adc.Convert(-3.4 * lsb_v), -3);
  EXPECT_EQ(adc.Convert(vref_v), 0x7FFFFF);
  EXPECT_EQ(adc.Convert(5.0), 0x7FFFFF);
  EXPECT_EQ(adc.Convert(-vref_v), -0x800000);
  EXPECT_EQ(adc.Convert(-1e9), -0x800000);
}

TEST(Ads1254, InlBowPeaksAtConfiguredPpmOfFsr) {
  // INL is defined against the straight line through the end points; the configured value is
  // the largest deviation as ppm of FSR = 2·VREF. Measured from a sweep: end-point line from
  // ±(VREF − 1 mV), max deviation found to within 1 LSB (0.06 ppm FSR) of quantisation.
  Ads1254Params p = Ideal();
  p.effects.inl = true;
  p.inl_ppm_fsr = -12.0;
  Ads1254 adc(p, 1);
  const double lsb_v = adc.NominalLsbV();
  const double lo_v = -(p.vref_v - 1e-3);
  const double hi_v = p.vref_v - 1e-3;
  const double lo_cnt = adc.Convert(lo_v);
  const double hi_cnt = adc.Convert(hi_v);
  double worst_v = 0.0;
  for (int i = 0; i <= 400; ++i) {
    const double v = lo_v + (hi_v - lo_v) * i / 400.0;
    const double line_cnt = lo_cnt + (hi_cnt - lo_cnt) * (v - lo_v) / (hi_v - lo_v);
    const double dev_v = (adc.Convert(v) - line_cnt) * lsb_v;
    if (std::fabs(dev_v) > std::fabs(worst_v)) worst_v = dev_v;
  }
  const double fsr_v = 2.0 * p.vref_v;
  EXPECT_NEAR(worst_v / fsr_v * 1e6, -12.0, 2.0 * lsb_v / fsr_v * 1e6);
}

TEST(Ads1254, ReferenceErrorIsAGainError) {
  // The code scales with 1/VREF_true: +2000 ppm of reference reads 2000 ppm low (to first
  // order; exactly 1/(1 + 2e-3)). Tolerance: 1 LSB of rounding.
  Ads1254Params p = Ideal();
  p.effects.reference_error = true;
  p.reference_error_ppm = 2000.0;
  Ads1254 adc(p, 1);
  const double input_v = 3.0;
  EXPECT_NEAR(adc.Convert(input_v), input_v / adc.NominalLsbV() / 1.002, 1.0);
}

TEST(Ads1254, EachEffectChangesOutputOnlyWhenOn) {
  // With a term off, changing its parameter leaves every code unchanged; with it on, the code
  // moves by the expected amount (at least many LSB for these parameter changes).
  const double input_v = 1.234;
  auto code_of = [&](Ads1254Params p) { return Ads1254(p, 99).Convert(input_v); };
  Ads1254Params base = Ads1254Params::Typical();
  base.effects = Ads1254Effects{};
  Ads1254Params changed = base;
  changed.inl_ppm_fsr = -15.0;
  changed.reference_error_ppm = -5000.0;
  changed.noise_uv_rms = 500.0;
  changed.averaging_count = 1;
  EXPECT_EQ(code_of(base), code_of(changed));

  Ads1254Params inl_on = base;
  inl_on.effects.inl = true;
  inl_on.inl_ppm_fsr = 10.0;
  // 10 ppm · 8.192 V · (1 − (1.234/4.096)²) = 74.5 µV = 152.6 LSB.
  EXPECT_NEAR(code_of(inl_on) - code_of(base), 152.6, 1.0);

  Ads1254Params ref_on = base;
  ref_on.effects.reference_error = true;
  ref_on.reference_error_ppm = -5000.0;
  // 1.234 V / 0.488 µV = 2 527 232 codes; ×(1/0.995 − 1) = 12 699 codes.
  EXPECT_NEAR(code_of(ref_on) - code_of(base), 12699.7, 1.0);

  Ads1254Params noise_on = base;
  noise_on.effects.noise = true;
  EXPECT_NE(code_of(noise_on), code_of(base));
}

TEST(Ads1254, DeterministicPerSeed) {
  const Ads1254Params p = Ads1254Params::Draw(42);
  Ads1254 a(p, 5);
  Ads1254 b(p, 5);
  Ads1254 c(p, 6);
  bool any_difference = false;
  for (int i = 0; i < 100; ++i) {
    const int32_t code_a = a.Convert(0.5);
    EXPECT_EQ(code_a, b.Convert(0.5));
    any_difference |= code_a != c.Convert(0.5);
  }
  EXPECT_TRUE(any_difference);
  EXPECT_EQ(Ads1254Params::Draw(42), p);
  EXPECT_NE(Ads1254Params::Draw(43), p);
}

TEST(Ads1254, DrawStaysInsideDatasheetLimits) {
  // INL is a datasheet maximum (15 ppm FSR): no drawn part may exceed it.
  for (uint64_t seed = 0; seed < 500; ++seed) {
    const Ads1254Params p = Ads1254Params::Draw(seed);
    EXPECT_LE(std::fabs(p.inl_ppm_fsr), 15.0);
    EXPECT_LE(std::fabs(p.reference_error_ppm), 2000.0);
  }
}

TEST(Ads1254, NonFiniteInputThrows) {
  Ads1254 adc(Ads1254Params::Typical(), 1);
  try {
    adc.Convert(std::nan(""));
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("input_v = nan"));
  }
}

TEST(Ads1254, JsonRoundTripIsExact) {
  for (const Ads1254Params& p : {Ads1254Params::Typical(), Ads1254Params::Draw(3)}) {
    const nlohmann::json j = nlohmann::json::parse(p.ToJson().dump());
    EXPECT_EQ(Ads1254Params::FromJson(common::ParamReader(j, "test")), p);
  }
}

TEST(Ads1254, DrawnJsonIsStablePerSeed) {
  EXPECT_EQ(Ads1254Params::Draw(11).ToJson().dump(), Ads1254Params::Draw(11).ToJson().dump());
  EXPECT_NE(Ads1254Params::Draw(11).ToJson().dump(), Ads1254Params::Draw(12).ToJson().dump());
}

std::string FromJsonError(const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json j = Ads1254Params::Typical().ToJson();
  edit(j);
  try {
    Ads1254Params::FromJson(common::ParamReader(j, "adc.json"));
  } catch (const common::ParamError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Ads1254, BadJsonNamesPathAndRange) {
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j.erase("vref_v"); }),
              AllOf(HasSubstr("adc.json"), HasSubstr("$.vref_v"), HasSubstr("missing")));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) {
                j["vref_mv"] = j["vref_v"];
                j.erase("vref_v");
              }),
              HasSubstr("$.vref_v"));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["inl_ppm_fsr"] = 20.0; }),
              AllOf(HasSubstr("$.inl_ppm_fsr"), HasSubstr("[-15, 15] ppm FSR")));
  EXPECT_THAT(
      FromJsonError([](nlohmann::json& j) { j["noise_uv_rms"] = "NaN"; }),
      AllOf(HasSubstr("$.noise_uv_rms"), HasSubstr("expected a number"), HasSubstr("[0, 1000]")));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["averaging_count"] = 5000; }),
              AllOf(HasSubstr("$.averaging_count"), HasSubstr("[1, 4096]")));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["effects"]["dither"] = true; }),
              AllOf(HasSubstr("$.effects.dither"), HasSubstr("unknown key")));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["vref_mv"] = 4096; }),
              AllOf(HasSubstr("$.vref_mv"), HasSubstr("unknown key")));
}

}  // namespace
}  // namespace adahrs::sensor_sim
