#include "sensor_sim/pressure_bridge.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/units.h"

namespace adahrs::sensor_sim {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

constexpr PressureBridgeKind kStatic = PressureBridgeKind::kAbsolute;
constexpr PressureBridgeKind kPitot = PressureBridgeKind::kDifferential;

// Typical part with only the named effects on (and never noise unless asked).
PressureBridgeParams TypicalWith(const std::function<void(PressureBridgeEffects&)>& enable) {
  PressureBridgeParams p = PressureBridgeParams::Typical(kStatic);
  p.effects = PressureBridgeEffects{};
  enable(p.effects);
  return p;
}

PressureBridgeOutput Once(const PressureBridgeParams& p, double pressure_pa, double temp_c) {
  PressureBridge bridge(p, 1);
  return bridge.Step({pressure_pa, temp_c});
}

TEST(PressureBridge, FullScaleOutputAsConfigured) {
  // FSO = V_B·S = 1 mA · 5 kΩ · 18 mV/V = 90 mV at 25 °C (physics.md §3.1: 75…100 mV), with
  // every nominal term but noise on: FSO is defined to include the nonlinearity.
  PressureBridgeParams p = PressureBridgeParams::Typical(kStatic);
  p.effects.noise = false;
  const double fs_pa = common::PsiToPa(15.0);
  const double fso_v = Once(p, fs_pa, 25.0).signal_v - Once(p, 0.0, 25.0).signal_v;
  EXPECT_NEAR(fso_v, 0.090, 1e-12);
  // Zero output: o0·V_B = 0.1 mV/V · 5 V.
  EXPECT_NEAR(Once(p, 0.0, 25.0).signal_v, 0.5e-3, 1e-15);
}

TEST(PressureBridge, BfslNonlinearityAsConfigured) {
  // Least-squares straight line through a dense sweep 0…FS at 25 °C; largest residual in % FSO
  // must equal the configured 0.15 % (and its sign: ends above the line). A sweep of n + 1
  // points differs from the continuous BFSL by O(1/n): 2000 points, tolerance 0.2 % of NL.
  for (double nl_pct : {0.15, -0.25}) {
    PressureBridgeParams p = TypicalWith([](PressureBridgeEffects& e) { e.nonlinearity = true; });
    p.nonlinearity_bfsl_pct_fso = nl_pct;
    PressureBridge bridge(p, 1);
    const int n = 2000;
    std::vector<double> x(n + 1), y(n + 1);
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i <= n; ++i) {
      x[i] = p.full_scale_pa * i / n;
      y[i] = bridge.Step({x[i], 25.0}).signal_v;
      sx += x[i];
      sy += y[i];
      sxx += x[i] * x[i];
      sxy += x[i] * y[i];
    }
    const double m = n + 1;
    const double slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
    const double intercept = (sy - slope * sx) / m;
    double worst = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double r = y[i] - (intercept + slope * x[i]);
      if (std::fabs(r) > std::fabs(worst)) worst = r;
    }
    const double fso_v = y[n] - y[0];
    EXPECT_NEAR(worst / fso_v * 100.0, nl_pct, 2e-3 * std::fabs(nl_pct));
    EXPECT_NEAR(fso_v, 0.090, 1e-12);
  }
}

TEST(PressureBridgeBridgeVoltage, TempcoAsConfigured) {
  // V_B = I·R_B0·(1 + αΔT + βΔT²): 5 V at 25 °C, slope α·V_B = 13 mV/°C (physics.md §3.2, D:
  // "about 10 mV/°C" at 4 kΩ). Symmetric difference ±1 °C cancels β exactly.
  const PressureBridgeParams p = TypicalWith([](PressureBridgeEffects& e) { e.bridge_tcr = true; });
  EXPECT_NEAR(Once(p, 0.0, 25.0).bridge_v, 5.0, 1e-12);
  const double slope_v_per_c = (Once(p, 0.0, 26.0).bridge_v - Once(p, 0.0, 24.0).bridge_v) / 2.0;
  EXPECT_NEAR(slope_v_per_c, 2600e-6 * 5.0, 1e-12);
  // Curvature: V_B(25+20) + V_B(25−20) − 2·V_B(25) = 2·β·20²·V_B0.
  const double curvature_v = Once(p, 0.0, 45.0).bridge_v + Once(p, 0.0, 5.0).bridge_v - 10.0;
  EXPECT_NEAR(curvature_v, 2.0 * 8e-6 * 400.0 * 5.0, 1e-12);
}

TEST(PressureBridgeBridgeVoltage, CurrentSourceTempcoAddsToApparentTcr) {
  // physics.md §3.2: the current source's tempco adds directly to the apparent TCR (to first
  // order: the symmetric difference cancels α·k_I·ΔT² but leaves k_I·β·ΔT³·V_B0 = −1.6e-9 V/°C).
  PressureBridgeParams p = TypicalWith([](PressureBridgeEffects& e) {
    e.bridge_tcr = true;
    e.excitation_tempco = true;
  });
  p.excitation_tempco_ppm_per_c = -40.0;
  const double slope_v_per_c = (Once(p, 0.0, 26.0).bridge_v - Once(p, 0.0, 24.0).bridge_v) / 2.0;
  EXPECT_NEAR(slope_v_per_c, (2600e-6 - 40e-6) * 5.0, 2e-9);
}

TEST(PressureBridgeBridgeVoltage, PressureDependenceAsConfigured) {
  // γ_P = 200 ppm of R_B at full scale: the thermometer reads 200e-6/2600e-6 = 0.077 °C high.
  const PressureBridgeParams p =
      TypicalWith([](PressureBridgeEffects& e) { e.resistance_pressure = true; });
  EXPECT_NEAR(
      Once(p, p.full_scale_pa, 25.0).bridge_v / Once(p, 0.0, 25.0).bridge_v - 1.0, 200e-6, 1e-12);
}

TEST(PressureBridge, NetSpanTempcoUnderConstantCurrent) {
  // physics.md §3.2 [AVS]: under constant current the span tempco is TCS + TCR: with the
  // typical t1 = −2500 and α = +2600 ppm/°C, +100 ppm/°C of FSO per °C. Symmetric difference
  // ±1 °C leaves only third-order terms (α·t2 + β·t1 ≈ 2e-8, i.e. 0.02 ppm).
  PressureBridgeParams p = TypicalWith([](PressureBridgeEffects& e) {
    e.bridge_tcr = true;
    e.span_tempco = true;
  });
  auto fso = [&](double t_c) {
    return Once(p, p.full_scale_pa, t_c).signal_v - Once(p, 0.0, t_c).signal_v;
  };
  const double tc_ppm_per_c = (fso(26.0) - fso(24.0)) / 2.0 / fso(25.0) * 1e6;
  EXPECT_NEAR(tc_ppm_per_c, 100.0, 0.1);
}

TEST(PressureBridge, OffsetTempcoAsConfigured) {
  // Zero output at ΔT = +20 °C: V_B·(o0 + o1·20 + o2·400) with V_B fixed (TCR off):
  // 5 V · (100 + 20 + 4) µV/V = 0.62 mV.
  const PressureBridgeParams p =
      TypicalWith([](PressureBridgeEffects& e) { e.offset_tempco = true; });
  EXPECT_NEAR(Once(p, 0.0, 45.0).signal_v, 5.0 * 124e-6, 1e-15);
  EXPECT_NEAR(Once(p, 0.0, 25.0).signal_v, 5.0 * 100e-6, 1e-15);
}

// Sweeps 0 → FS → 0 at 25 °C and returns (rising, falling) output at mid-scale.
std::pair<double, double> UpDownAtMidScale(const PressureBridgeParams& p) {
  PressureBridge bridge(p, 3);
  const int n = 200;
  double up_v = 0.0;
  double down_v = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double out = bridge.Step({p.full_scale_pa * i / n, 25.0}).signal_v;
    if (i == n / 2) up_v = out;
  }
  for (int i = n; i >= 0; --i) {
    const double out = bridge.Step({p.full_scale_pa * i / n, 25.0}).signal_v;
    if (i == n / 2) down_v = out;
  }
  return {up_v, down_v};
}

TEST(PressureBridge, PressureHysteresisOnlyWhenOn) {
  // Falling minus rising branch at mid-scale = h_P·FSO = 0.075 % · 90 mV = 67.5 µV when on
  // (the 20 % FS span has fully developed after 50 % FS of travel); exactly 0 when off, even
  // with a large configured h_P. Rounding only: 1e-15 V.
  PressureBridgeParams off = PressureBridgeParams::Typical(kStatic);
  off.effects.noise = false;
  off.pressure_hysteresis_pct_fso = 1.0;
  const auto [up_off, down_off] = UpDownAtMidScale(off);
  EXPECT_EQ(down_off - up_off, 0.0);

  PressureBridgeParams on = off;
  on.pressure_hysteresis_pct_fso = 0.075;
  on.effects.pressure_hysteresis = true;
  const auto [up_on, down_on] = UpDownAtMidScale(on);
  EXPECT_NEAR(down_on - up_on, 0.075e-2 * 0.090, 1e-15);
  EXPECT_NEAR((down_on - up_on) / 0.090 * 100.0, 0.075, 1e-9);
}

TEST(PressureBridge, ThermalHysteresisOnlyWhenOn) {
  // Zero output at 25 °C after a 25 → 70 → 25 °C excursion minus after 25 → −20 → 25 °C:
  // h_T·FSO = 0.15 % · 90 mV = 135 µV when on (45 °C of travel > 20 °C span), 0 when off.
  auto after_excursion = [](const PressureBridgeParams& p, double extreme_c) {
    PressureBridge bridge(p, 3);
    double out = 0.0;
    for (int i = 0; i <= 100; ++i) bridge.Step({0.0, 25.0 + (extreme_c - 25.0) * i / 100});
    for (int i = 100; i >= 0; --i)
      out = bridge.Step({0.0, 25.0 + (extreme_c - 25.0) * i / 100}).signal_v;
    return out;
  };
  PressureBridgeParams off = PressureBridgeParams::Typical(kStatic);
  off.effects.noise = false;
  EXPECT_EQ(after_excursion(off, 70.0) - after_excursion(off, -20.0), 0.0);
  PressureBridgeParams on = off;
  on.effects.thermal_hysteresis = true;
  EXPECT_NEAR(after_excursion(on, 70.0) - after_excursion(on, -20.0), 0.15e-2 * 0.090, 1e-15);
}

TEST(PressureBridge, NoiseRmsAsConfigured) {
  // 20 000 samples: relative standard error of the rms 0.5 %; tolerance 3 % (6 sigma).
  PressureBridgeParams p = TypicalWith([](PressureBridgeEffects& e) { e.noise = true; });
  p.noise_uv_rms = 2.0;
  PressureBridge bridge(p, 17);
  const double clean_v = Once(TypicalWith([](PressureBridgeEffects&) {}), 50000.0, 25.0).signal_v;
  double sum2 = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double e = bridge.Step({50000.0, 25.0}).signal_v - clean_v;
    sum2 += e * e;
  }
  EXPECT_NEAR(std::sqrt(sum2 / n) * 1e6, 2.0, 0.06);
}

TEST(PressureBridge, SelfHeatingPower) {
  // I²·R_B = (1 mA)²·5 kΩ = 5 mW at 25 °C (physics.md §6 row 6: bridge ≈ 4…9 mW), following
  // V_B with temperature; 0 with the effect off.
  PressureBridgeParams p = TypicalWith([](PressureBridgeEffects& e) {
    e.self_heating = true;
    e.bridge_tcr = true;
  });
  PressureBridge bridge(p, 1);
  EXPECT_NEAR(bridge.SelfHeatingW(), 5e-3, 1e-15);
  // 5 mW · 150 °C/W = 0.75 °C (physics.md §3.2: 1…2 °C at 9 mW, E).
  EXPECT_NEAR(bridge.SelfHeatingRiseC(), 0.75, 1e-12);
  bridge.Step({0.0, 45.0});
  EXPECT_NEAR(bridge.SelfHeatingW(), 1e-3 * Once(p, 0.0, 45.0).bridge_v, 1e-15);
  PressureBridge cold(TypicalWith([](PressureBridgeEffects& e) { e.bridge_tcr = true; }), 1);
  cold.Step({0.0, 45.0});
  EXPECT_EQ(cold.SelfHeatingW(), 0.0);
}

struct EffectCase {
  const char* name;
  std::function<void(PressureBridgeEffects&)> enable;
  std::function<void(PressureBridgeParams&)> perturb;
};

TEST(PressureBridge, EachEffectChangesOutputOnlyWhenOn) {
  // For each effect: with everything else off, perturbing its parameters leaves a pressure and
  // temperature path bit-identical when the effect is off and changes it when it is on.
  const std::vector<EffectCase> cases = {
      {"noise", [](auto& e) { e.noise = true; }, [](auto& p) { p.noise_uv_rms = 50.0; }},
      {"bridge_tcr",
       [](auto& e) { e.bridge_tcr = true; },
       [](auto& p) {
         p.bridge_tcr_ppm_per_c = 1000.0;
         p.bridge_tcr2_ppm_per_c2 = -20.0;
       }},
      {"excitation_tempco",
       [](auto& e) { e.excitation_tempco = true; },
       [](auto& p) { p.excitation_tempco_ppm_per_c = 100.0; }},
      {"resistance_pressure",
       [](auto& e) { e.resistance_pressure = true; },
       [](auto& p) { p.resistance_pressure_ppm_per_fs = -3000.0; }},
      {"offset_tempco",
       [](auto& e) { e.offset_tempco = true; },
       [](auto& p) {
         p.offset_tc_uv_per_v_per_c = -20.0;
         p.offset_tc2_uv_per_v_per_c2 = 1.0;
       }},
      {"span_tempco",
       [](auto& e) { e.span_tempco = true; },
       [](auto& p) {
         p.span_tc_ppm_per_c = 0.0;
         p.span_tc2_ppm_per_c2 = 30.0;
       }},
      {"nonlinearity",
       [](auto& e) { e.nonlinearity = true; },
       [](auto& p) { p.nonlinearity_bfsl_pct_fso = -1.0; }},
      {"pressure_hysteresis",
       [](auto& e) { e.pressure_hysteresis = true; },
       [](auto& p) {
         p.pressure_hysteresis_pct_fso = 1.0;
         p.pressure_hysteresis_span_pct_fs = 5;
       }},
      {"thermal_hysteresis",
       [](auto& e) { e.thermal_hysteresis = true; },
       [](auto& p) {
         p.thermal_hysteresis_pct_fso = 1.0;
         p.thermal_hysteresis_span_c = 2.0;
       }},
  };
  auto path = [](const PressureBridgeParams& p) {
    PressureBridge bridge(p, 21);
    std::vector<double> out;
    for (int i = 0; i <= 40; ++i) {
      const double pressure_pa = p.full_scale_pa * (i <= 20 ? i : 40 - i) / 20.0;
      const double temp_c = 25.0 + 30.0 * std::sin(0.3 * i);
      const PressureBridgeOutput o = bridge.Step({pressure_pa, temp_c});
      out.push_back(o.signal_v);
      out.push_back(o.bridge_v);
    }
    return out;
  };
  for (const EffectCase& c : cases) {
    PressureBridgeParams base = TypicalWith([](PressureBridgeEffects&) {});
    PressureBridgeParams perturbed = base;
    c.perturb(perturbed);
    EXPECT_EQ(path(base), path(perturbed)) << c.name << " off";
    c.enable(base.effects);
    c.enable(perturbed.effects);
    EXPECT_NE(path(base), path(perturbed)) << c.name << " on";
  }
}

TEST(PressureBridge, DeterministicPerSeedAndKind) {
  const PressureBridgeParams p = PressureBridgeParams::Draw(kPitot, 8);
  EXPECT_EQ(PressureBridgeParams::Draw(kPitot, 8), p);
  EXPECT_NE(PressureBridgeParams::Draw(kStatic, 8).sensitivity_mv_per_v, p.sensitivity_mv_per_v);
  PressureBridge a(p, 4);
  PressureBridge b(p, 4);
  for (int i = 0; i < 50; ++i) {
    const PressureBridgeInput in{1000.0 * i, 20.0 + 0.1 * i};
    const PressureBridgeOutput oa = a.Step(in);
    const PressureBridgeOutput ob = b.Step(in);
    EXPECT_EQ(oa.signal_v, ob.signal_v);
    EXPECT_EQ(oa.bridge_v, ob.bridge_v);
  }
}

TEST(PressureBridge, DrawnPartsStayInsideTheDocumentedRanges) {
  // Draw() must respect its own documented 3-sigma limits (docs/models/pressure-bridge.md):
  // S 18 ± 2.5 mV/V (FSO 77.5…102.5 mV at V_B = 5 V, cf. 75…100 mV in physics.md §3.1),
  // NL 0.15 ± 0.1 % FSO (§3.1: 0.1…0.25), R_B 5 ± 1 kΩ (§3.1: 4…6 kΩ).
  for (uint64_t seed = 0; seed < 300; ++seed) {
    const PressureBridgeParams p = PressureBridgeParams::Draw(kStatic, seed);
    EXPECT_GE(p.sensitivity_mv_per_v, 15.5);
    EXPECT_LE(p.sensitivity_mv_per_v, 20.5);
    EXPECT_GE(p.nonlinearity_bfsl_pct_fso, 0.05);
    EXPECT_LE(p.nonlinearity_bfsl_pct_fso, 0.25);
    EXPECT_GE(p.bridge_resistance_ohm, 4000.0);
    EXPECT_LE(p.bridge_resistance_ohm, 6000.0);
  }
}

// Each drawn part has its own hysteresis spans (20 +- 10 % FS and 20 +- 10 degC at 3 sigma, E):
// a calibration that assumed the typical part's would be wrong on every unit by a different amount.
TEST(PressureBridge, DrawnPartsHaveTheirOwnHysteresisSpans) {
  double min_p = 1e9, max_p = 0.0, min_t = 1e9, max_t = 0.0;
  for (uint64_t seed = 0; seed < 300; ++seed) {
    const PressureBridgeParams p = PressureBridgeParams::Draw(kStatic, seed);
    min_p = std::min(min_p, p.pressure_hysteresis_span_pct_fs);
    max_p = std::max(max_p, p.pressure_hysteresis_span_pct_fs);
    min_t = std::min(min_t, p.thermal_hysteresis_span_c);
    max_t = std::max(max_t, p.thermal_hysteresis_span_c);
  }
  EXPECT_GE(min_p, 10.0);
  EXPECT_LE(max_p, 30.0);
  EXPECT_LT(min_p, 14.0);
  EXPECT_GT(max_p, 26.0);
  EXPECT_GE(min_t, 10.0);
  EXPECT_LE(max_t, 30.0);
  EXPECT_NE(PressureBridgeParams::Draw(kStatic, 1).thermal_hysteresis_span_c,
            PressureBridgeParams::Draw(kStatic, 2).thermal_hysteresis_span_c);
}

// Under the play-operator law the loop between fully developed branches is still h_P (the weights
// sum to one), while a loop of a tenth of the span is larger than the travel law's, whose branch
// leaves a reversal with zero slope.
TEST(PressureBridge, PlayLawKeepsTheFullLoopAndChangesItsShape) {
  PressureBridgeParams travel = PressureBridgeParams::Typical(kStatic);
  travel.effects.noise = false;
  travel.effects.pressure_hysteresis = true;
  PressureBridgeParams play = travel;
  play.hysteresis_law = HysteresisLaw::kPlayOperators;
  const auto [up_r, down_r] = UpDownAtMidScale(play);
  EXPECT_NEAR(down_r - up_r, 0.075e-2 * 0.090, 1e-9);
  auto small_loop_v = [](const PressureBridgeParams& p) {
    PressureBridge b(p, 1);
    const double fs = p.full_scale_pa, dp = 0.02 * fs;
    for (double x : {0.5 * fs, fs, 0.5 * fs + dp}) b.Step({x, 25.0});
    const double up = b.Step({0.5 * fs, 25.0}).signal_v;
    b.Step({0.5 * fs - dp, 25.0});
    return b.Step({0.5 * fs, 25.0}).signal_v - up;
  };
  EXPECT_GT(std::abs(small_loop_v(play)), 3.0 * std::abs(small_loop_v(travel)));
}

TEST(PressureBridge, JsonRoundTripIsExactAndStable) {
  PressureBridgeParams play = PressureBridgeParams::Draw(kStatic, 6);
  play.hysteresis_law = HysteresisLaw::kPlayOperators;
  for (const PressureBridgeParams& p : {PressureBridgeParams::Typical(kStatic),
                                        PressureBridgeParams::Typical(kPitot),
                                        PressureBridgeParams::Draw(kStatic, 5),
                                        PressureBridgeParams::Draw(kPitot, 5),
                                        play}) {
    const nlohmann::json j = nlohmann::json::parse(p.ToJson().dump());
    EXPECT_EQ(PressureBridgeParams::FromJson(common::ParamReader(j, "bridge.json")), p);
  }
  EXPECT_EQ(PressureBridgeParams::Draw(kPitot, 77).ToJson().dump(),
            PressureBridgeParams::Draw(kPitot, 77).ToJson().dump());
}

std::string FromJsonError(const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json j = PressureBridgeParams::Typical(kPitot).ToJson();
  edit(j);
  try {
    PressureBridgeParams::FromJson(common::ParamReader(j, "pitot.json"));
  } catch (const common::ParamError& e) {
    return e.what();
  }
  return "no error";
}

TEST(PressureBridge, BadJsonNamesPathAndRange) {
  EXPECT_THAT(
      FromJsonError([](nlohmann::json& j) { j.erase("sensitivity_mv_per_v"); }),
      AllOf(HasSubstr("pitot.json"), HasSubstr("$.sensitivity_mv_per_v"), HasSubstr("missing")));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["bridge_resistance_kohm"] = 5.0; }),
              AllOf(HasSubstr("$.bridge_resistance_kohm"), HasSubstr("unknown key")));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["bridge_tcr_ppm_per_c"] = 9000.0; }),
              AllOf(HasSubstr("$.bridge_tcr_ppm_per_c"),
                    HasSubstr("out of range"),
                    HasSubstr("[-5000, 5000] ppm/degC")));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["noise_uv_rms"] = "nan"; }),
              AllOf(HasSubstr("$.noise_uv_rms"),
                    HasSubstr("expected a number"),
                    HasSubstr("[0, 1000] uV rms")));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["kind"] = "gauge"; }),
              AllOf(HasSubstr("$.kind"), HasSubstr("\"gauge\""), HasSubstr("differential")));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["hysteresis_law"] = "jiles_atherton"; }),
              AllOf(HasSubstr("$.hysteresis_law"), HasSubstr("play_operators")));
  // A file written before the key existed reads as the travel law.
  nlohmann::json old = PressureBridgeParams::Typical(kPitot).ToJson();
  old.erase("hysteresis_law");
  EXPECT_EQ(PressureBridgeParams::FromJson(common::ParamReader(old, "old.json")).hysteresis_law,
            HysteresisLaw::kTravelPreisach);
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["effects"].erase("nonlinearity"); }),
              AllOf(HasSubstr("$.effects.nonlinearity"), HasSubstr("missing")));
}

TEST(PressureBridge, NonFiniteInputThrows) {
  PressureBridge bridge(PressureBridgeParams::Typical(kStatic), 1);
  try {
    bridge.Step({std::nan(""), 25.0});
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("pressure_pa = nan"));
  }
}

}  // namespace
}  // namespace adahrs::sensor_sim
