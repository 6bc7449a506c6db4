#include "sensor_sim/oat_probe.h"

#include <sstream>
#include <stdexcept>
#include <string>

#include "common/random.h"

namespace adahrs::sensor_sim {
namespace {

constexpr double kPercent = 1e-2;
constexpr double kWattsPerMilliwatt = 1e-3;

// IEC 60751:2008 Callendar–Van Dusen coefficients (definitions of the standard curve).
constexpr double kCvdA_per_c = 3.9083e-3;
constexpr double kCvdB_per_c2 = -5.775e-7;
constexpr double kCvdC_per_c4 = -4.183e-12;
constexpr double kMinTemp_c = -200.0;
constexpr double kMaxTemp_c = 850.0;

// Class B tolerance at 0 °C, ±0.3 °C, as a fraction of R0: 0.3·A = 0.117 %.
constexpr double kClassBR0Tolerance_pct = 0.3 * kCvdA_per_c / kPercent;
constexpr double kSeriesToR0Ratio = 10.0;      // E: design choice, keeps I²R < 0.2 mW
constexpr double kSeriesTolerance_pct = 0.1;   // E: 0.1 % resistor
constexpr double kExcitation_v = 4.096;        // the ADS1254 reference (ratiometric)
constexpr double kLeadResistance_ohm = 0.5;    // E: two wires, ~1 m of AWG 26 each way
constexpr double kDissipation_mw_per_c = 5.0;  // E: ventilated probe

const char* ElementName(RtdElement element) {
  return element == RtdElement::kPt500 ? "PT500" : "PT1000";
}

}  // namespace

OatProbeEffects OatProbeEffects::Nominal() {
  return {.rtd_tolerance = true, .lead_resistance = true, .self_heating = false};
}

OatProbeEffects OatProbeEffects::All() {
  return {.rtd_tolerance = true, .lead_resistance = true, .self_heating = true};
}

double RtdNominalR0Ohm(RtdElement element) {
  return element == RtdElement::kPt500 ? 500.0 : 1000.0;
}

OatProbeParams OatProbeParams::Typical(RtdElement element) {
  OatProbeParams p;
  p.element = element;
  p.r0_error_pct = 0.0;
  p.cvd_a_per_c = kCvdA_per_c;
  p.cvd_b_per_c2 = kCvdB_per_c2;
  p.cvd_c_per_c4 = kCvdC_per_c4;
  p.series_resistance_ohm = kSeriesToR0Ratio * RtdNominalR0Ohm(element);
  p.excitation_v = kExcitation_v;
  p.lead_resistance_ohm = kLeadResistance_ohm;
  p.dissipation_mw_per_c = kDissipation_mw_per_c;
  p.effects = OatProbeEffects::Nominal();
  return p;
}

OatProbeParams OatProbeParams::Draw(RtdElement element, uint64_t seed) {
  common::Rng rng(common::Rng::Derive(seed, element == RtdElement::kPt500 ? 0x0A7500 : 0x0A71000));
  OatProbeParams p = Typical(element);
  p.r0_error_pct = rng.Tolerance(0.0, kClassBR0Tolerance_pct);
  p.series_resistance_ohm = rng.Tolerance(
      p.series_resistance_ohm, kSeriesTolerance_pct * kPercent * p.series_resistance_ohm);
  p.lead_resistance_ohm = rng.Tolerance(kLeadResistance_ohm, 0.2);
  p.dissipation_mw_per_c = rng.Tolerance(kDissipation_mw_per_c, 2.0);
  p.effects = OatProbeEffects::All();
  return p;
}

nlohmann::json OatProbeParams::ToJson() const {
  return {{"element", ElementName(element)},
          {"r0_error_pct", r0_error_pct},
          {"cvd_a_per_c", cvd_a_per_c},
          {"cvd_b_per_c2", cvd_b_per_c2},
          {"cvd_c_per_c4", cvd_c_per_c4},
          {"series_resistance_ohm", series_resistance_ohm},
          {"excitation_v", excitation_v},
          {"lead_resistance_ohm", lead_resistance_ohm},
          {"dissipation_mw_per_c", dissipation_mw_per_c},
          {"effects",
           {{"rtd_tolerance", effects.rtd_tolerance},
            {"lead_resistance", effects.lead_resistance},
            {"self_heating", effects.self_heating}}}};
}

OatProbeParams OatProbeParams::FromJson(const common::ParamReader& r) {
  OatProbeParams p;
  const std::string element = r.String("element");
  if (element == "PT500") {
    p.element = RtdElement::kPt500;
  } else if (element == "PT1000") {
    p.element = RtdElement::kPt1000;
  } else {
    r.Fail(r.path() + ".element", "\"" + element + "\" is not one of \"PT500\", \"PT1000\"");
  }
  p.r0_error_pct = r.Number("r0_error_pct", -1.0, 1.0, "%");
  // The curve coefficients are the standard's; allow a characterised element's own values
  // within a few percent of them.
  p.cvd_a_per_c = r.Number("cvd_a_per_c", 3.8e-3, 4.0e-3, "1/degC");
  p.cvd_b_per_c2 = r.Number("cvd_b_per_c2", -6.5e-7, -5.0e-7, "1/degC^2");
  p.cvd_c_per_c4 = r.Number("cvd_c_per_c4", -6e-12, -2e-12, "1/degC^4");
  p.series_resistance_ohm = r.Number("series_resistance_ohm", 10.0, 1e6, "ohm");
  p.excitation_v = r.Number("excitation_v", 0.1, 5.0, "V");
  p.lead_resistance_ohm = r.Number("lead_resistance_ohm", 0.0, 100.0, "ohm");
  p.dissipation_mw_per_c = r.Number("dissipation_mw_per_c", 0.1, 1000.0, "mW/degC");
  const common::ParamReader e = r.Child("effects");
  p.effects.rtd_tolerance = e.Flag("rtd_tolerance");
  p.effects.lead_resistance = e.Flag("lead_resistance");
  p.effects.self_heating = e.Flag("self_heating");
  e.ExpectAllKeysUsed();
  r.ExpectAllKeysUsed();
  return p;
}

OatProbe::OatProbe(const OatProbeParams& params) : params_(params) {
  const OatProbeEffects& on = params_.effects;
  r0_ohm_ = RtdNominalR0Ohm(params_.element) *
            (1.0 + (on.rtd_tolerance ? params_.r0_error_pct * kPercent : 0.0));
  lead_ohm_ = on.lead_resistance ? params_.lead_resistance_ohm : 0.0;
  dissipation_w_per_c_ = params_.dissipation_mw_per_c * kWattsPerMilliwatt;
}

double OatProbe::RtdResistanceOhm(double rtd_temp_c) const {
  if (!(rtd_temp_c >= kMinTemp_c && rtd_temp_c <= kMaxTemp_c)) {
    std::ostringstream message;
    message << "OatProbe: rtd_temp_c = " << rtd_temp_c
            << " degC is outside the IEC 60751 range [-200, 850] degC";
    throw std::domain_error(message.str());
  }
  const double t = rtd_temp_c;
  double ratio = 1.0 + (params_.cvd_a_per_c + params_.cvd_b_per_c2 * t) * t;
  if (t < 0.0) ratio += params_.cvd_c_per_c4 * (t - 100.0) * t * t * t;
  return r0_ohm_ * ratio;
}

double OatProbe::SignalV(double air_temp_c) const {
  const double series_ohm = params_.series_resistance_ohm;
  const double v_exc = params_.excitation_v;
  double rtd_ohm = RtdResistanceOhm(air_temp_c);
  if (params_.effects.self_heating) {
    for (int i = 0; i < 2; ++i) {
      const double current_a = v_exc / (series_ohm + rtd_ohm + lead_ohm_);
      rtd_ohm =
          RtdResistanceOhm(air_temp_c + current_a * current_a * rtd_ohm / dissipation_w_per_c_);
    }
  }
  const double measured_ohm = rtd_ohm + lead_ohm_;
  return v_exc * measured_ohm / (series_ohm + measured_ohm);
}

}  // namespace adahrs::sensor_sim
