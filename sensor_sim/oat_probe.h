// Outside-air-temperature probe of the ADS unit: a platinum RTD (PT500 or PT1000, IEC 60751
// Callendar-Van Dusen curve, valid −200…850 °C) at the bottom of a voltage divider, excited from
// the ADS1254 reference so that the reading is ratiometric, with the element's R0 tolerance,
// two-wire lead resistance and self-heating (two fixed-point iterations); SignalV() is the voltage
// an ADS1254 channel (ads1254.h) digitises. Throws std::domain_error outside −200…850 °C.
// Units: °C, Ω, V, mW/°C via the names.
// Equations, IEC coefficients, parameters and sources: docs/models/oat-probe.md.
// Left out: the probe's thermal time constant and total-temperature recovery (the input is the
// element temperature with no self-heating), series-resistor tempco and the board temperature,
// insulation leakage, thermoelectric EMFs, noise (the ADS1254 channel adds it).
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

#include "common/param_reader.h"

namespace adahrs::sensor_sim {

/// Platinum element type: R0 = 500 Ω or 1000 Ω at 0 °C.
enum class RtdElement { kPt500, kPt1000 };

/// Separately switchable physical terms of the probe model.
struct OatProbeEffects {
  bool rtd_tolerance = false;    ///< the unit's R0 differs from nominal
  bool lead_resistance = false;  ///< two-wire lead resistance in series with the element
  bool self_heating = false;     ///< I²R heating of the element

  /// R0 error and lead resistance on (offsets a calibration absorbs); self-heating off.
  static OatProbeEffects Nominal();
  /// Every term on.
  static OatProbeEffects All();
  bool operator==(const OatProbeEffects&) const = default;
};

struct OatProbeParams {
  RtdElement element = RtdElement::kPt1000;
  double r0_error_pct = 0.0;           ///< e_R0, this element's R0 deviation
  double cvd_a_per_c = 0.0;            ///< Callendar–Van Dusen A
  double cvd_b_per_c2 = 0.0;           ///< Callendar–Van Dusen B
  double cvd_c_per_c4 = 0.0;           ///< Callendar–Van Dusen C (below 0 °C)
  double series_resistance_ohm = 0.0;  ///< R_s, from the excitation to the element
  double excitation_v = 0.0;           ///< V_exc across the divider
  double lead_resistance_ohm = 0.0;    ///< R_lead, both wires together
  double dissipation_mw_per_c = 0.0;   ///< δ, self-heating dissipation constant
  OatProbeEffects effects;

  /// Typical probe of the given element, R_s = 10·R0, V_exc = 4.096 V, Nominal() effects.
  static OatProbeParams Typical(RtdElement element);
  /// One probe drawn from the class-B / estimate distributions (deterministic), All() effects.
  static OatProbeParams Draw(RtdElement element, uint64_t seed);
  nlohmann::json ToJson() const;
  /// Reads every key with its allowed range; throws ParamError naming the JSON path.
  static OatProbeParams FromJson(const common::ParamReader& reader);
  bool operator==(const OatProbeParams&) const = default;
};

/// Nominal R0 of an element type, Ω.
double RtdNominalR0Ohm(RtdElement element);

/// Stateless probe model (no noise of its own).
class OatProbe {
 public:
  explicit OatProbe(const OatProbeParams& params);

  /// Element resistance at element temperature `rtd_temp_c` (with the R0 error if on), Ω.
  double RtdResistanceOhm(double rtd_temp_c) const;
  /// Divider output for air temperature `air_temp_c`, V.
  double SignalV(double air_temp_c) const;
  const OatProbeParams& params() const { return params_; }

 private:
  OatProbeParams params_;
  double r0_ohm_;
  double lead_ohm_;
  double dissipation_w_per_c_;
};

}  // namespace adahrs::sensor_sim
