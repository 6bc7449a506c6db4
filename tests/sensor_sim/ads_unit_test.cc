#include "sensor_sim/ads_unit.h"

#include <cmath>

#include <gtest/gtest.h>

namespace adahrs::sensor_sim {
namespace {

constexpr int kFrames = 200;

AdsUnitParams QuietUnit(uint64_t seed) {
  AdsUnitParams p = AdsUnitParams::Draw("ADS-T", seed, ModelProfile::kNominal);
  p.static_thermal.effects = DieThermalEffects::Nominal();
  p.pitot_thermal.effects = DieThermalEffects::Nominal();
  return p;
}

struct Mean {
  double ps = 0, pt = 0, ps_temp = 0, pt_temp = 0, oat = 0;
};

Mean Average(AdsUnit& unit, const AdsStimulus& s) {
  Mean m;
  for (int i = 0; i < kFrames; ++i) {
    const AdsRawFrame f = unit.Step(s);
    m.ps += f.ps_cnt;
    m.pt += f.pt_cnt;
    m.ps_temp += f.ps_temp_cnt;
    m.pt_temp += f.pt_temp_cnt;
    m.oat += f.oat_cnt;
  }
  for (double* v : {&m.ps, &m.pt, &m.ps_temp, &m.pt_temp, &m.oat}) *v /= kFrames;
  return m;
}

double CodesPerVolt(const AdsUnitParams& p) { return 1.0 / (p.adc.vref_v / (1 << 23)); }

// Expected pressure slope from the bridge's datasheet-style parameters: output = V_B · S · P/FS at
// the reference temperature, V_B = I·R_B. The ADC converts at 2^23/VREF codes per volt.
TEST(AdsUnit, PressureSlopesFollowTheBridgeSensitivity) {
  const AdsUnitParams p = QuietUnit(31);
  for (bool pitot : {false, true}) {
    const PressureBridgeParams& b = pitot ? p.pitot_bridge : p.static_bridge;
    AdsUnit unit(p, 1, b.reference_temp_c);
    AdsStimulus lo, hi;
    lo.air_temp_c = hi.air_temp_c = b.reference_temp_c;
    lo.oat_c = hi.oat_c = b.reference_temp_c;
    if (pitot) {
      lo.qc_pa = 2000.0;
      hi.qc_pa = 30000.0;
    } else {
      lo.ps_pa = 30000.0;
      hi.ps_pa = 100000.0;
    }
    const Mean a = Average(unit, lo), c = Average(unit, hi);
    const double dp_pa = pitot ? hi.qc_pa - lo.qc_pa : hi.ps_pa - lo.ps_pa;
    const double v_b = b.excitation_current_ma * 1e-3 * b.bridge_resistance_ohm;
    const double expected =
        v_b * b.sensitivity_mv_per_v * 1e-3 * dp_pa / b.full_scale_pa * CodesPerVolt(p);
    const double measured = pitot ? c.pt - a.pt : c.ps - a.ps;
    // Each end point may sit off the best-fit straight line by the BFSL nonlinearity (% FSO), so
    // the secant differs from the BFSL slope by at most twice that in counts; the ADC reference
    // error (ppm) adds 0.1 % at most.
    const double fso_cnt = v_b * b.sensitivity_mv_per_v * 1e-3 * CodesPerVolt(p);
    const double allowed =
        2.0 * std::abs(b.nonlinearity_bfsl_pct_fso) / 100.0 * fso_cnt + 0.001 * expected;
    EXPECT_NEAR(measured, expected, allowed) << (pitot ? "pitot" : "static");
  }
}

TEST(AdsUnit, BridgeVoltageChannelsAreThermometers) {
  const AdsUnitParams p = QuietUnit(32);
  AdsUnit cold(p, 1, 0.0), warm(p, 1, 40.0);
  AdsStimulus s;
  s.air_temp_c = s.oat_c = 0.0;
  const Mean a = Average(cold, s);
  s.air_temp_c = s.oat_c = 40.0;
  const Mean c = Average(warm, s);
  const PressureBridgeParams& b = p.static_bridge;
  // dV_B/dT ≈ V_B0 · (α + k_I) at constant current (physics.md §3.2: ~+0.26 %/°C).
  const double v_b = b.excitation_current_ma * 1e-3 * b.bridge_resistance_ohm;
  const double tc_per_c = (b.bridge_tcr_ppm_per_c + b.excitation_tempco_ppm_per_c) * 1e-6;
  const double expected = v_b * tc_per_c * 40.0 * p.bridge_divider_ratio * CodesPerVolt(p);
  // The second-order TCR term over 40 °C stays below 5 % of the linear one.
  EXPECT_NEAR(c.ps_temp - a.ps_temp, expected, 0.05 * expected);
  EXPECT_GT(c.oat - a.oat, 0.0);  // the RTD divider rises with temperature
}

TEST(AdsUnit, DeterministicAndRoundTrips) {
  const AdsUnitParams p = AdsUnitParams::Draw("ADS-0007", 33, ModelProfile::kTruth);
  AdsUnit a(p, 5, 20.0), b(p, 5, 20.0);
  AdsStimulus s;
  s.qc_pa = 1630.3;
  for (int i = 0; i < 50; ++i) {
    const AdsRawFrame fa = a.Step(s), fb = b.Step(s);
    EXPECT_EQ(fa.ps_cnt, fb.ps_cnt);
    EXPECT_EQ(fa.pt_temp_cnt, fb.pt_temp_cnt);
  }
  const nlohmann::json j = nlohmann::json::parse(p.ToJson().dump());
  EXPECT_EQ(AdsUnitParams::FromJson(common::ParamReader(j, "truth.json")).ToJson(), p.ToJson());
}

TEST(AdsUnit, NominalAndTruthDifferOnlyByEffects) {
  nlohmann::json n = AdsUnitParams::Draw("A", 34, ModelProfile::kNominal).ToJson();
  nlohmann::json t = AdsUnitParams::Draw("A", 34, ModelProfile::kTruth).ToJson();
  EXPECT_NE(n, t);
  for (auto* j : {&n, &t}) {
    for (const char* key :
         {"static_bridge", "pitot_bridge", "adc", "oat", "static_thermal", "pitot_thermal"}) {
      (*j)[key].erase("effects");
    }
  }
  EXPECT_EQ(n, t);
}

TEST(AdsUnit, BadDividerIsRefusedWithPath) {
  nlohmann::json j = AdsUnitParams::Draw("A", 35, ModelProfile::kTruth).ToJson();
  j["bridge_divider_ratio"] = 2.0;
  try {
    AdsUnitParams::FromJson(common::ParamReader(j, "ads.json"));
    FAIL();
  } catch (const common::ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("$.bridge_divider_ratio"), std::string::npos);
  }
}

}  // namespace
}  // namespace adahrs::sensor_sim
