#include "sensor_sim/oat_probe.h"

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace adahrs::sensor_sim {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

OatProbeParams Ideal(RtdElement element) {
  OatProbeParams p = OatProbeParams::Typical(element);
  p.effects = OatProbeEffects{};
  return p;
}

struct TableRow {
  double temp_c;
  double pt100_ohm;
};

// IEC 60751 PT100 reference table (resistance to 0.01 Ω); PT500/PT1000 are 5×/10× these.
constexpr TableRow kIec60751Table[] = {
    {-200.0, 18.52},
    {-100.0, 60.26},
    {-40.0, 84.27},
    {0.0, 100.00},
    {50.0, 119.40},
    {100.0, 138.51},
    {200.0, 175.86},
    {850.0, 390.48},
};

TEST(OatProbe, ResistanceMatchesIec60751Table) {
  // Half the table's last digit (0.005 Ω for PT100), scaled with R0.
  for (RtdElement element : {RtdElement::kPt500, RtdElement::kPt1000}) {
    const OatProbe probe(Ideal(element));
    const double scale = RtdNominalR0Ohm(element) / 100.0;
    for (const TableRow& row : kIec60751Table) {
      EXPECT_NEAR(probe.RtdResistanceOhm(row.temp_c), scale * row.pt100_ohm, scale * 0.005)
          << row.temp_c << " degC";
    }
  }
}

TEST(OatProbe, IdealDividerOutput) {
  // PT1000 at 0 °C with R_s = 10 kΩ from 4.096 V: 4.096·1000/11000 = 0.3723636 V.
  const OatProbe probe(Ideal(RtdElement::kPt1000));
  EXPECT_NEAR(probe.SignalV(0.0), 4.096 * 1000.0 / 11000.0, 1e-15);
}

// Temperature whose ideal RTD resistance gives `signal_v` through the ideal divider: inverts
// the divider analytically and the IEC curve by bisection (independent of the model code path).
double ApparentTempC(const OatProbeParams& p, double signal_v) {
  const double r_ohm = p.series_resistance_ohm * signal_v / (p.excitation_v - signal_v);
  const OatProbe ideal(Ideal(p.element));
  double lo = -200.0;
  double hi = 850.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (ideal.RtdResistanceOhm(mid) < r_ohm ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Above 0 °C the IEC curve is the quadratic R/R0 = 1 + A·t + B·t², so the temperature of a
// resistance ratio has the closed form t = (−A + sqrt(A² + 4·B·(ratio − 1)))/(2·B).
double IecTempAboveZeroC(double ratio) {
  const double a = 3.9083e-3;
  const double b = -5.775e-7;
  return (-a + std::sqrt(a * a + 4.0 * b * (ratio - 1.0))) / (2.0 * b);
}

TEST(OatProbe, LeadResistanceReadsAsTemperatureOffset) {
  // 0.5 Ω of lead adds 0.5/R0 to the ratio at 0 °C: ≈ 0.128 °C high on a PT1000, ≈ 0.256 °C on
  // a PT500. Tolerance 1e-9 °C: bisection and closed form both resolve far below that.
  for (RtdElement element : {RtdElement::kPt500, RtdElement::kPt1000}) {
    OatProbeParams p = Ideal(element);
    p.effects.lead_resistance = true;
    const double expected_c = IecTempAboveZeroC(1.0 + 0.5 / RtdNominalR0Ohm(element));
    EXPECT_NEAR(ApparentTempC(p, OatProbe(p).SignalV(0.0)), expected_c, 1e-9);
    EXPECT_NEAR(expected_c, 0.5 / (RtdNominalR0Ohm(element) * 3.9083e-3), 2e-5);
  }
}

TEST(OatProbe, SelfHeatingRaisesElementByPowerOverDissipation) {
  // At −30 °C, PT1000 (R ≈ 881.6 Ω) with 10 kΩ from 4.096 V: I ≈ 0.376 mA, P ≈ 0.125 mW;
  // δ = 5 mW/°C gives ≈ 0.025 °C. The expected rise here uses the power at the air temperature;
  // at the element temperature the power is higher by about (dR/R/dT)·rise ≈ 0.0045·0.025, i.e.
  // 1.1e-4 of the rise (2.8e-6 °C): tolerance 5e-6 °C.
  OatProbeParams p = Ideal(RtdElement::kPt1000);
  p.effects.self_heating = true;
  const double air_c = -30.0;
  const double r_ohm = OatProbe(Ideal(RtdElement::kPt1000)).RtdResistanceOhm(air_c);
  const double i_a = 4.096 / (10000.0 + r_ohm);
  const double rise_c = i_a * i_a * r_ohm / 5e-3;
  EXPECT_NEAR(ApparentTempC(p, OatProbe(p).SignalV(air_c)) - air_c, rise_c, 5e-6);
  EXPECT_GT(ApparentTempC(p, OatProbe(p).SignalV(air_c)) - air_c, rise_c);
}

TEST(OatProbe, R0ErrorReadsAsClassTolerance) {
  // +0.117 % R0 is the class-B limit, 0.3 °C at 0 °C to first order (IEC 60751 class B:
  // ±(0.3 + 0.005|t|) °C); exactly the closed-form temperature of ratio 1.0011725.
  OatProbeParams p = Ideal(RtdElement::kPt1000);
  p.effects.rtd_tolerance = true;
  p.r0_error_pct = 0.3 * 3.9083e-3 * 100.0;
  const double apparent_c = ApparentTempC(p, OatProbe(p).SignalV(0.0));
  EXPECT_NEAR(apparent_c, IecTempAboveZeroC(1.0 + 0.3 * 3.9083e-3), 1e-9);
  EXPECT_NEAR(apparent_c, 0.3, 2e-5);
}

TEST(OatProbe, EachEffectChangesOutputOnlyWhenOn) {
  struct Case {
    const char* name;
    std::function<void(OatProbeEffects&)> enable;
    std::function<void(OatProbeParams&)> perturb;
  };
  const Case cases[] = {
      {"rtd_tolerance",
       [](auto& e) { e.rtd_tolerance = true; },
       [](auto& p) { p.r0_error_pct = 0.5; }},
      {"lead_resistance",
       [](auto& e) { e.lead_resistance = true; },
       [](auto& p) { p.lead_resistance_ohm = 3.0; }},
      {"self_heating",
       [](auto& e) { e.self_heating = true; },
       [](auto& p) { p.dissipation_mw_per_c = 0.5; }},
  };
  for (const Case& c : cases) {
    OatProbeParams base = Ideal(RtdElement::kPt1000);
    OatProbeParams perturbed = base;
    c.perturb(perturbed);
    for (double t_c : {-55.0, 0.0, 40.0}) {
      EXPECT_EQ(OatProbe(base).SignalV(t_c), OatProbe(perturbed).SignalV(t_c)) << c.name;
    }
    c.enable(base.effects);
    c.enable(perturbed.effects);
    EXPECT_NE(OatProbe(base).SignalV(-55.0), OatProbe(perturbed).SignalV(-55.0)) << c.name;
  }
}

TEST(OatProbe, DrawIsDeterministicAndWithinClassB) {
  EXPECT_EQ(OatProbeParams::Draw(RtdElement::kPt500, 9),
            OatProbeParams::Draw(RtdElement::kPt500, 9));
  EXPECT_NE(OatProbeParams::Draw(RtdElement::kPt500, 9),
            OatProbeParams::Draw(RtdElement::kPt500, 10));
  for (uint64_t seed = 0; seed < 300; ++seed) {
    const OatProbeParams p = OatProbeParams::Draw(RtdElement::kPt1000, seed);
    EXPECT_LE(std::fabs(p.r0_error_pct), 0.3 * 3.9083e-3 * 100.0 + 1e-12);
  }
}

TEST(OatProbe, JsonRoundTripIsExactAndStable) {
  for (const OatProbeParams& p : {OatProbeParams::Typical(RtdElement::kPt500),
                                  OatProbeParams::Draw(RtdElement::kPt1000, 2)}) {
    const nlohmann::json j = nlohmann::json::parse(p.ToJson().dump());
    EXPECT_EQ(OatProbeParams::FromJson(common::ParamReader(j, "oat.json")), p);
  }
  EXPECT_EQ(OatProbeParams::Draw(RtdElement::kPt1000, 4).ToJson().dump(),
            OatProbeParams::Draw(RtdElement::kPt1000, 4).ToJson().dump());
}

std::string FromJsonError(const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json j = OatProbeParams::Typical(RtdElement::kPt1000).ToJson();
  edit(j);
  try {
    OatProbeParams::FromJson(common::ParamReader(j, "oat.json"));
  } catch (const common::ParamError& e) {
    return e.what();
  }
  return "no error";
}

TEST(OatProbe, BadJsonNamesPathAndRange) {
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j.erase("excitation_v"); }),
              AllOf(HasSubstr("oat.json"), HasSubstr("$.excitation_v"), HasSubstr("missing")));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["element"] = "PT100"; }),
              AllOf(HasSubstr("$.element"), HasSubstr("PT100")));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["lead_resistance_ohm"] = -1.0; }),
              AllOf(HasSubstr("$.lead_resistance_ohm"), HasSubstr("[0, 100] ohm")));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["dissipation_mw_per_c"] = "NaN"; }),
              AllOf(HasSubstr("$.dissipation_mw_per_c"), HasSubstr("expected a number")));
  EXPECT_THAT(FromJsonError([](nlohmann::json& j) { j["series_resistance_kohm"] = 10.0; }),
              AllOf(HasSubstr("$.series_resistance_kohm"), HasSubstr("unknown key")));
}

TEST(OatProbe, OutOfRangeTemperatureThrows) {
  const OatProbe probe(OatProbeParams::Typical(RtdElement::kPt1000));
  try {
    probe.SignalV(-250.0);
    ADD_FAILURE() << "no exception";
  } catch (const std::domain_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("rtd_temp_c = -250"));
  }
}

}  // namespace
}  // namespace adahrs::sensor_sim
