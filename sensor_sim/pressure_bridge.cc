#include "sensor_sim/pressure_bridge.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "common/units.h"

namespace adahrs::sensor_sim {
namespace {

constexpr double kPpm = 1e-6;
constexpr double kPercent = 1e-2;
constexpr double kAmpsPerMilliamp = 1e-3;
constexpr double kVoltsPerMillivolt = 1e-3;
constexpr double kVoltsPerMicrovolt = 1e-6;

// Typical part (physics.md §3.1/§3.2; status tags in docs/models/pressure-bridge.md).
constexpr double kFullScale_psi = 15.0;                  // brief / R
constexpr double kReferenceTemp_c = 25.0;                // datasheet reference condition
constexpr double kExcitation_ma = 1.0;                   // R (1.0 mA keeps I·R_B inside 5 V)
constexpr double kBridgeResistance_ohm = 5000.0;         // V [MAX1450]
constexpr double kTcr_ppm_per_c = 2600.0;                // V [MAX1450]
constexpr double kTcr2_ppm_per_c2 = 8.0;                 // E
constexpr double kResistancePressure_ppm = 200.0;        // E
constexpr double kSensitivity_mv_per_v = 18.0;           // D: FSO 90 mV (R/E) at V_B = 5 V
constexpr double kSpanTc_ppm_per_c = -2500.0;            // D: net span tempco +100 ppm/°C
constexpr double kSpanTc2_ppm_per_c2 = 1.0;              // E
constexpr double kOffset_mv_per_v = 0.1;                 // R/E: ±1…2 mV zero offset
constexpr double kOffsetTc_uv_per_v_per_c = 1.0;         // R/E: ±0.5…1 % FSO over 0…70 °C
constexpr double kOffsetTc2_uv_per_v_per_c2 = 0.01;      // E
constexpr double kNonlinearity_pct_fso = 0.15;           // R/E: ±0.1…0.25 % FSO BFSL
constexpr double kPressureHysteresis_pct_fso = 0.075;    // E (KPY33 ±0.1 % V)
constexpr double kPressureHysteresisSpan_pct_fs = 20.0;  // E
constexpr double kThermalHysteresis_pct_fso = 0.15;      // E (KPY33 ±0.1 typ V)
constexpr double kThermalHysteresisSpan_c = 20.0;        // E
constexpr double kNoise_uv_rms = 1.0;           // D: Johnson noise of 5 kΩ at 300 K over ~10 kHz
constexpr double kSelfHeating_c_per_w = 150.0;  // E: 100…200 °C/W

// The play-operator law's working range of die temperature: the range FromJson accepts for a
// reference.
constexpr double kPlayLawMinTemp_c = -55.0;
constexpr double kPlayLawMaxTemp_c = 125.0;

const char* KindName(PressureBridgeKind kind) {
  return kind == PressureBridgeKind::kAbsolute ? "absolute" : "differential";
}

}  // namespace

const char* ToString(HysteresisLaw law) {
  return law == HysteresisLaw::kTravelPreisach ? "travel_preisach" : "play_operators";
}

PressureBridgeEffects PressureBridgeEffects::Nominal() {
  PressureBridgeEffects e;
  e.noise = true;
  e.bridge_tcr = true;
  e.offset_tempco = true;
  e.span_tempco = true;
  e.nonlinearity = true;
  return e;
}

PressureBridgeEffects PressureBridgeEffects::All() {
  return {true, true, true, true, true, true, true, true, true, true};
}

PressureBridgeParams PressureBridgeParams::Typical(PressureBridgeKind kind) {
  PressureBridgeParams p;
  p.kind = kind;
  p.full_scale_pa = common::PsiToPa(kFullScale_psi);
  p.reference_temp_c = kReferenceTemp_c;
  p.excitation_current_ma = kExcitation_ma;
  p.excitation_tempco_ppm_per_c = 0.0;
  p.bridge_resistance_ohm = kBridgeResistance_ohm;
  p.bridge_tcr_ppm_per_c = kTcr_ppm_per_c;
  p.bridge_tcr2_ppm_per_c2 = kTcr2_ppm_per_c2;
  p.resistance_pressure_ppm_per_fs = kResistancePressure_ppm;
  p.sensitivity_mv_per_v = kSensitivity_mv_per_v;
  p.span_tc_ppm_per_c = kSpanTc_ppm_per_c;
  p.span_tc2_ppm_per_c2 = kSpanTc2_ppm_per_c2;
  p.offset_mv_per_v = kOffset_mv_per_v;
  p.offset_tc_uv_per_v_per_c = kOffsetTc_uv_per_v_per_c;
  p.offset_tc2_uv_per_v_per_c2 = kOffsetTc2_uv_per_v_per_c2;
  p.nonlinearity_bfsl_pct_fso = kNonlinearity_pct_fso;
  p.pressure_hysteresis_pct_fso = kPressureHysteresis_pct_fso;
  p.pressure_hysteresis_span_pct_fs = kPressureHysteresisSpan_pct_fs;
  p.thermal_hysteresis_pct_fso = kThermalHysteresis_pct_fso;
  p.thermal_hysteresis_span_c = kThermalHysteresisSpan_c;
  p.noise_uv_rms = kNoise_uv_rms;
  p.self_heating_c_per_w = kSelfHeating_c_per_w;
  p.effects = PressureBridgeEffects::Nominal();
  return p;
}

PressureBridgeParams PressureBridgeParams::Draw(PressureBridgeKind kind, uint64_t seed) {
  // Each ± below is a 3-sigma screening limit (Rng::Tolerance); the spreads are E unless the
  // doc says otherwise.
  common::Rng rng(
      common::Rng::Derive(seed, kind == PressureBridgeKind::kAbsolute ? 0x1230A : 0x1230D));
  PressureBridgeParams p = Typical(kind);
  p.excitation_current_ma = rng.Tolerance(kExcitation_ma, 0.005 * kExcitation_ma);
  p.excitation_tempco_ppm_per_c = rng.Tolerance(0.0, 25.0);
  p.bridge_resistance_ohm = rng.Tolerance(kBridgeResistance_ohm, 1000.0);
  p.bridge_tcr_ppm_per_c = rng.Tolerance(kTcr_ppm_per_c, 300.0);
  p.bridge_tcr2_ppm_per_c2 = rng.Tolerance(kTcr2_ppm_per_c2, 4.0);
  p.resistance_pressure_ppm_per_fs = rng.Tolerance(0.0, 500.0);
  p.sensitivity_mv_per_v = rng.Tolerance(kSensitivity_mv_per_v, 2.5);
  p.span_tc_ppm_per_c = rng.Tolerance(kSpanTc_ppm_per_c, 200.0);
  p.span_tc2_ppm_per_c2 = rng.Tolerance(kSpanTc2_ppm_per_c2, 2.0);
  p.offset_mv_per_v = rng.Tolerance(0.0, 0.4);
  p.offset_tc_uv_per_v_per_c = rng.Tolerance(0.0, 3.0);
  p.offset_tc2_uv_per_v_per_c2 = rng.Tolerance(0.0, 0.03);
  p.nonlinearity_bfsl_pct_fso = rng.Tolerance(kNonlinearity_pct_fso, 0.1);
  p.pressure_hysteresis_pct_fso = rng.Tolerance(kPressureHysteresis_pct_fso, 0.025);
  p.thermal_hysteresis_pct_fso = rng.Tolerance(kThermalHysteresis_pct_fso, 0.05);
  p.self_heating_c_per_w = rng.Tolerance(kSelfHeating_c_per_w, 50.0);
  p.pressure_hysteresis_span_pct_fs = rng.Tolerance(kPressureHysteresisSpan_pct_fs, 10.0);
  p.thermal_hysteresis_span_c = rng.Tolerance(kThermalHysteresisSpan_c, 10.0);
  p.effects = PressureBridgeEffects::All();
  return p;
}

nlohmann::json PressureBridgeParams::ToJson() const {
  const PressureBridgeEffects& e = effects;
  return {{"kind", KindName(kind)},
          {"full_scale_pa", full_scale_pa},
          {"reference_temp_c", reference_temp_c},
          {"excitation_current_ma", excitation_current_ma},
          {"excitation_tempco_ppm_per_c", excitation_tempco_ppm_per_c},
          {"bridge_resistance_ohm", bridge_resistance_ohm},
          {"bridge_tcr_ppm_per_c", bridge_tcr_ppm_per_c},
          {"bridge_tcr2_ppm_per_c2", bridge_tcr2_ppm_per_c2},
          {"resistance_pressure_ppm_per_fs", resistance_pressure_ppm_per_fs},
          {"sensitivity_mv_per_v", sensitivity_mv_per_v},
          {"span_tc_ppm_per_c", span_tc_ppm_per_c},
          {"span_tc2_ppm_per_c2", span_tc2_ppm_per_c2},
          {"offset_mv_per_v", offset_mv_per_v},
          {"offset_tc_uv_per_v_per_c", offset_tc_uv_per_v_per_c},
          {"offset_tc2_uv_per_v_per_c2", offset_tc2_uv_per_v_per_c2},
          {"nonlinearity_bfsl_pct_fso", nonlinearity_bfsl_pct_fso},
          {"pressure_hysteresis_pct_fso", pressure_hysteresis_pct_fso},
          {"pressure_hysteresis_span_pct_fs", pressure_hysteresis_span_pct_fs},
          {"thermal_hysteresis_pct_fso", thermal_hysteresis_pct_fso},
          {"thermal_hysteresis_span_c", thermal_hysteresis_span_c},
          {"noise_uv_rms", noise_uv_rms},
          {"self_heating_c_per_w", self_heating_c_per_w},
          {"hysteresis_law", ToString(hysteresis_law)},
          {"effects",
           {{"noise", e.noise},
            {"bridge_tcr", e.bridge_tcr},
            {"excitation_tempco", e.excitation_tempco},
            {"resistance_pressure", e.resistance_pressure},
            {"offset_tempco", e.offset_tempco},
            {"span_tempco", e.span_tempco},
            {"nonlinearity", e.nonlinearity},
            {"pressure_hysteresis", e.pressure_hysteresis},
            {"thermal_hysteresis", e.thermal_hysteresis},
            {"self_heating", e.self_heating}}}};
}

PressureBridgeParams PressureBridgeParams::FromJson(const common::ParamReader& r) {
  PressureBridgeParams p;
  const std::string kind = r.String("kind");
  if (kind == "absolute") {
    p.kind = PressureBridgeKind::kAbsolute;
  } else if (kind == "differential") {
    p.kind = PressureBridgeKind::kDifferential;
  } else {
    r.Fail(r.path() + ".kind", "\"" + kind + "\" is not one of \"absolute\", \"differential\"");
  }
  p.full_scale_pa = r.Number("full_scale_pa", 1e3, 1e6, "Pa");
  p.reference_temp_c = r.Number("reference_temp_c", -55.0, 125.0, "degC");
  p.excitation_current_ma = r.Number("excitation_current_ma", 0.05, 5.0, "mA");
  p.excitation_tempco_ppm_per_c = r.Number("excitation_tempco_ppm_per_c", -500, 500, "ppm/degC");
  p.bridge_resistance_ohm = r.Number("bridge_resistance_ohm", 500.0, 50000.0, "ohm");
  p.bridge_tcr_ppm_per_c = r.Number("bridge_tcr_ppm_per_c", -5000.0, 5000.0, "ppm/degC");
  p.bridge_tcr2_ppm_per_c2 = r.Number("bridge_tcr2_ppm_per_c2", -100.0, 100.0, "ppm/degC^2");
  p.resistance_pressure_ppm_per_fs =
      r.Number("resistance_pressure_ppm_per_fs", -10000.0, 10000.0, "ppm/FS");
  p.sensitivity_mv_per_v = r.Number("sensitivity_mv_per_v", 1.0, 100.0, "mV/V");
  p.span_tc_ppm_per_c = r.Number("span_tc_ppm_per_c", -5000.0, 5000.0, "ppm/degC");
  p.span_tc2_ppm_per_c2 = r.Number("span_tc2_ppm_per_c2", -100.0, 100.0, "ppm/degC^2");
  p.offset_mv_per_v = r.Number("offset_mv_per_v", -20.0, 20.0, "mV/V");
  p.offset_tc_uv_per_v_per_c = r.Number("offset_tc_uv_per_v_per_c", -100.0, 100.0, "uV/V/degC");
  p.offset_tc2_uv_per_v_per_c2 = r.Number("offset_tc2_uv_per_v_per_c2", -10.0, 10.0, "uV/V/degC^2");
  p.nonlinearity_bfsl_pct_fso = r.Number("nonlinearity_bfsl_pct_fso", -2.0, 2.0, "% FSO");
  p.pressure_hysteresis_pct_fso = r.Number("pressure_hysteresis_pct_fso", -2.0, 2.0, "% FSO");
  p.pressure_hysteresis_span_pct_fs =
      r.Number("pressure_hysteresis_span_pct_fs", 0.1, 100.0, "% FS");
  p.thermal_hysteresis_pct_fso = r.Number("thermal_hysteresis_pct_fso", -2.0, 2.0, "% FSO");
  p.thermal_hysteresis_span_c = r.Number("thermal_hysteresis_span_c", 0.1, 200.0, "degC");
  p.noise_uv_rms = r.Number("noise_uv_rms", 0.0, 1000.0, "uV rms");
  p.self_heating_c_per_w = r.Number("self_heating_c_per_w", 0.0, 2000.0, "degC/W");
  if (r.Has("hysteresis_law")) {
    const std::string law = r.String("hysteresis_law");
    if (law == ToString(HysteresisLaw::kTravelPreisach)) {
      p.hysteresis_law = HysteresisLaw::kTravelPreisach;
    } else if (law == ToString(HysteresisLaw::kPlayOperators)) {
      p.hysteresis_law = HysteresisLaw::kPlayOperators;
    } else {
      r.Fail(r.path() + ".hysteresis_law",
             "\"" + law + "\" is not one of \"travel_preisach\", \"play_operators\"");
    }
  }
  const common::ParamReader e = r.Child("effects");
  p.effects.noise = e.Flag("noise");
  p.effects.bridge_tcr = e.Flag("bridge_tcr");
  p.effects.excitation_tempco = e.Flag("excitation_tempco");
  p.effects.resistance_pressure = e.Flag("resistance_pressure");
  p.effects.offset_tempco = e.Flag("offset_tempco");
  p.effects.span_tempco = e.Flag("span_tempco");
  p.effects.nonlinearity = e.Flag("nonlinearity");
  p.effects.pressure_hysteresis = e.Flag("pressure_hysteresis");
  p.effects.thermal_hysteresis = e.Flag("thermal_hysteresis");
  p.effects.self_heating = e.Flag("self_heating");
  e.ExpectAllKeysUsed();
  r.ExpectAllKeysUsed();
  return p;
}

PressureBridge::PressureBridge(const PressureBridgeParams& params, uint64_t noise_seed)
    : params_(params),
      rng_(noise_seed),
      pressure_hysteresis_(params.pressure_hysteresis_span_pct_fs * kPercent *
                           params.full_scale_pa),
      thermal_hysteresis_(params.thermal_hysteresis_span_c) {
  const PressureBridgeParams& p = params_;
  if (p.hysteresis_law == HysteresisLaw::kPlayOperators) {
    pressure_play_.emplace(
        p.pressure_hysteresis_span_pct_fs * kPercent * p.full_scale_pa, 0.0, p.full_scale_pa);
    thermal_play_.emplace(p.thermal_hysteresis_span_c, kPlayLawMinTemp_c, kPlayLawMaxTemp_c);
  }
  const PressureBridgeEffects& on = p.effects;
  inv_full_scale_per_pa_ = 1.0 / p.full_scale_pa;
  current0_a_ = p.excitation_current_ma * kAmpsPerMilliamp;
  current_tc_per_c_ = on.excitation_tempco ? p.excitation_tempco_ppm_per_c * kPpm : 0.0;
  resistance0_ohm_ = p.bridge_resistance_ohm;
  tcr_per_c_ = on.bridge_tcr ? p.bridge_tcr_ppm_per_c * kPpm : 0.0;
  tcr2_per_c2_ = on.bridge_tcr ? p.bridge_tcr2_ppm_per_c2 * kPpm : 0.0;
  resistance_pressure_per_fs_ =
      on.resistance_pressure ? p.resistance_pressure_ppm_per_fs * kPpm : 0.0;
  // Ratios of signal to V_B (V/V).
  const double sensitivity = p.sensitivity_mv_per_v * kVoltsPerMillivolt;
  offset0_ = p.offset_mv_per_v * kVoltsPerMillivolt;
  offset1_per_c_ = on.offset_tempco ? p.offset_tc_uv_per_v_per_c * kVoltsPerMicrovolt : 0.0;
  offset2_per_c2_ = on.offset_tempco ? p.offset_tc2_uv_per_v_per_c2 * kVoltsPerMicrovolt : 0.0;
  // K = 6·NL·S, S_lin = S − K (see header).
  quadratic_ = on.nonlinearity ? 6.0 * p.nonlinearity_bfsl_pct_fso * kPercent * sensitivity : 0.0;
  span_lin_ = sensitivity - quadratic_;
  span_tc_per_c_ = on.span_tempco ? p.span_tc_ppm_per_c * kPpm : 0.0;
  span_tc2_per_c2_ = on.span_tempco ? p.span_tc2_ppm_per_c2 * kPpm : 0.0;
  pressure_hysteresis_half_ =
      on.pressure_hysteresis ? 0.5 * p.pressure_hysteresis_pct_fso * kPercent * sensitivity : 0.0;
  thermal_hysteresis_half_ =
      on.thermal_hysteresis ? 0.5 * p.thermal_hysteresis_pct_fso * kPercent * sensitivity : 0.0;
  noise_v_rms_ = on.noise ? p.noise_uv_rms * kVoltsPerMicrovolt : 0.0;
  self_heating_w_ = on.self_heating ? current0_a_ * current0_a_ * resistance0_ohm_ : 0.0;
}

PressureBridgeOutput PressureBridge::Step(const PressureBridgeInput& input) {
  if (!std::isfinite(input.pressure_pa) || !std::isfinite(input.die_temp_c)) {
    throw std::invalid_argument(
        "PressureBridge::Step: pressure_pa = " + std::to_string(input.pressure_pa) +
        " Pa, die_temp_c = " + std::to_string(input.die_temp_c) + " degC must be finite");
  }
  const double dt_c = input.die_temp_c - params_.reference_temp_c;
  const double u = input.pressure_pa * inv_full_scale_per_pa_;
  const double current_a = current0_a_ * (1.0 + current_tc_per_c_ * dt_c);
  const double resistance_ohm = resistance0_ohm_ *
                                (1.0 + (tcr_per_c_ + tcr2_per_c2_ * dt_c) * dt_c) *
                                (1.0 + resistance_pressure_per_fs_ * u);
  const double bridge_v = current_a * resistance_ohm;

  double ratio = offset0_ + (offset1_per_c_ + offset2_per_c2_ * dt_c) * dt_c +
                 span_lin_ * (1.0 + (span_tc_per_c_ + span_tc2_per_c2_ * dt_c) * dt_c) * u +
                 quadratic_ * u * u;
  if (pressure_hysteresis_half_ != 0.0) {
    const double s_p = pressure_play_ ? pressure_play_->Update(input.pressure_pa)
                                      : pressure_hysteresis_.Update(input.pressure_pa);
    ratio += pressure_hysteresis_half_ * s_p;
  }
  if (thermal_hysteresis_half_ != 0.0) {
    const double s_t = thermal_play_ ? thermal_play_->Update(input.die_temp_c)
                                     : thermal_hysteresis_.Update(input.die_temp_c);
    ratio += thermal_hysteresis_half_ * s_t;
  }
  double signal_v = bridge_v * ratio;
  if (noise_v_rms_ > 0.0) signal_v += noise_v_rms_ * rng_.Normal();
  if (params_.effects.self_heating) self_heating_w_ = current_a * bridge_v;
  return {signal_v, bridge_v};
}

}  // namespace adahrs::sensor_sim
