// One IC Sensors / MSI model-1230 class piezoresistive pressure bridge under constant-current
// excitation (shared/physics.md §3.1, §3.2 and §6 rows 4, 6, 7): the static (absolute) or pitot
// (differential) sensor of the ADS air-data board. Step() takes the true pressure and die
// temperature and returns the differential bridge output and the voltage across the bridge V_B,
// which is the on-die thermometer. The output is V_B times a ratiometric polynomial in ΔT and
// u = pressure / full scale: offset and its tempcos, span and its tempcos, BFSL nonlinearity,
// pressure and thermal hysteresis (states of preisach_hysteresis.h or play_hysteresis.h), noise;
// R_B has its TCR (α, β) and pressure dependence, the current source its tempco. SelfHeatingW()
// reports I·V_B for the unit's thermal model, which owns the die temperature.
// Units: Pa, °C, V, A via the names; pressure absolute for kAbsolute, pitot − static for
// kDifferential (the same polynomial for both).
// Equations, FSO and BFSL definitions, parameters with sources: docs/models/pressure-bridge.md.
// Left out: common-mode sensitivity of the differential sensor, current-source-to-die gradient,
// long-term drift, creep, diaphragm g-sensitivity, media effects, overpressure, noise on V_B, 1/f
// noise. Every number marked R or E in physics.md is a parameter here, not a limit.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

#include <optional>

#include "common/param_reader.h"
#include "common/random.h"
#include "sensor_sim/play_hysteresis.h"
#include "sensor_sim/preisach_hysteresis.h"

namespace adahrs::sensor_sim {

/// What the sensor's reference port sees: vacuum (static sensor) or the other port (pitot).
enum class PressureBridgeKind { kAbsolute, kDifferential };

/// The law behind the hysteresis states s_P and s_T (see the header comment).
enum class HysteresisLaw { kTravelPreisach, kPlayOperators };

/// "travel_preisach" or "play_operators".
const char* ToString(HysteresisLaw law);

struct PressureBridgeInput {
  double pressure_pa;  ///< absolute (static sensor) or differential (pitot)
  double die_temp_c;   ///< temperature of the sensing die
};

struct PressureBridgeOutput {
  double signal_v;  ///< differential bridge output
  double bridge_v;  ///< voltage across the bridge (V_B), the temperature signal
};

/// Separately switchable physical terms of the bridge model.
struct PressureBridgeEffects {
  bool noise = false;                ///< white noise on the bridge output
  bool bridge_tcr = false;           ///< R_B temperature coefficients α, β (V_B thermometer)
  bool excitation_tempco = false;    ///< current-source tempco k_I
  bool resistance_pressure = false;  ///< R_B pressure dependence γ_P
  bool offset_tempco = false;        ///< zero tempco o1, o2
  bool span_tempco = false;          ///< ratiometric sensitivity tempco t1, t2
  bool nonlinearity = false;         ///< span nonlinearity K·u²
  bool pressure_hysteresis = false;  ///< history of the last pressure extreme
  bool thermal_hysteresis = false;   ///< history of the last temperature extreme
  bool self_heating = false;         ///< SelfHeatingW() reports I·V_B (else 0)

  /// What the reference calibration (a bivariate cubic in pressure and temperature counts)
  /// assumes: noise, TCR, offset and span tempcos, nonlinearity. Off: hysteresis (history),
  /// R_B pressure dependence, current-source tempco, self-heating.
  static PressureBridgeEffects Nominal();
  /// Every term on.
  static PressureBridgeEffects All();
  bool operator==(const PressureBridgeEffects&) const = default;
};

struct PressureBridgeParams {
  PressureBridgeKind kind = PressureBridgeKind::kAbsolute;
  double full_scale_pa = 0.0;                    ///< rated range 0…FS
  double reference_temp_c = 0.0;                 ///< origin of ΔT
  double excitation_current_ma = 0.0;            ///< I_0 at the reference temperature
  double excitation_tempco_ppm_per_c = 0.0;      ///< k_I
  double bridge_resistance_ohm = 0.0;            ///< R_B0 at reference temperature, zero pressure
  double bridge_tcr_ppm_per_c = 0.0;             ///< α
  double bridge_tcr2_ppm_per_c2 = 0.0;           ///< β
  double resistance_pressure_ppm_per_fs = 0.0;   ///< γ_P, R_B change at full scale
  double sensitivity_mv_per_v = 0.0;             ///< S = FSO/V_B at reference temperature
  double span_tc_ppm_per_c = 0.0;                ///< t1, of the ratio signal/V_B
  double span_tc2_ppm_per_c2 = 0.0;              ///< t2
  double offset_mv_per_v = 0.0;                  ///< o0
  double offset_tc_uv_per_v_per_c = 0.0;         ///< o1
  double offset_tc2_uv_per_v_per_c2 = 0.0;       ///< o2
  double nonlinearity_bfsl_pct_fso = 0.0;        ///< NL, signed
  double pressure_hysteresis_pct_fso = 0.0;      ///< h_P: falling minus rising branch
  double pressure_hysteresis_span_pct_fs = 0.0;  ///< travel after a reversal to full h_P
  double thermal_hysteresis_pct_fso = 0.0;       ///< h_T: after cooling minus after heating
  double thermal_hysteresis_span_c = 0.0;        ///< temperature travel to full h_T
  double noise_uv_rms = 0.0;                     ///< output noise per sample
  double self_heating_c_per_w = 0.0;             ///< die-to-case thermal resistance
  HysteresisLaw hysteresis_law = HysteresisLaw::kTravelPreisach;
  PressureBridgeEffects effects;

  /// The typical 0–15 psi part of the given kind, Nominal() effects.
  static PressureBridgeParams Typical(PressureBridgeKind kind);
  /// One part drawn from the datasheet / estimate distributions (deterministic per seed and
  /// kind), All() effects, the travel law; the hysteresis spans are drawn too (20 ± 10 % FS and
  /// 20 ± 10 °C at 3 sigma, E), so no two drawn parts share them.
  static PressureBridgeParams Draw(PressureBridgeKind kind, uint64_t seed);
  nlohmann::json ToJson() const;
  /// Reads every key with its allowed range; throws ParamError naming the JSON path. A file
  /// without "hysteresis_law" (written before the key existed) reads as the travel law.
  static PressureBridgeParams FromJson(const common::ParamReader& reader);
  bool operator==(const PressureBridgeParams&) const = default;
};

/// Stateful bridge model (the hysteresis operators remember the extremes that are not wiped out).
class PressureBridge {
 public:
  PressureBridge(const PressureBridgeParams& params, uint64_t noise_seed);

  /// Advances one sample. Throws std::invalid_argument for a non-finite input.
  PressureBridgeOutput Step(const PressureBridgeInput& input);

  /// Power dissipated in the bridge at the last Step (before the first: at the reference
  /// temperature and zero pressure), W; 0 when the self_heating effect is off.
  double SelfHeatingW() const { return self_heating_w_; }
  /// Steady-state die rise above the case from that power, SelfHeatingW()·self_heating_c_per_w,
  /// °C: what a die thermal model (die_thermal.h `self_heating_c`) needs.
  double SelfHeatingRiseC() const { return self_heating_w_ * params_.self_heating_c_per_w; }
  const PressureBridgeParams& params() const { return params_; }

 private:
  PressureBridgeParams params_;
  common::Rng rng_;
  PreisachHysteresis pressure_hysteresis_;
  PreisachHysteresis thermal_hysteresis_;
  std::optional<PlayHysteresis> pressure_play_;  // set under the play-operator law
  std::optional<PlayHysteresis> thermal_play_;
  // Coefficients with switched-off terms set to zero, precomputed in the constructor.
  double inv_full_scale_per_pa_;
  double current0_a_, current_tc_per_c_;
  double resistance0_ohm_, tcr_per_c_, tcr2_per_c2_, resistance_pressure_per_fs_;
  double offset0_, offset1_per_c_, offset2_per_c2_;
  double span_lin_, span_tc_per_c_, span_tc2_per_c2_, quadratic_;
  double pressure_hysteresis_half_, thermal_hysteresis_half_;
  double noise_v_rms_;
  double self_heating_w_;
};

}  // namespace adahrs::sensor_sim
