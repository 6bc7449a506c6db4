// One simulated ADS unit (the ADAHRS air-data board): a static (absolute 0–15 psi) and a pitot
// (differential 0–15 psi) model-1230 bridge under constant-current excitation, each with its own
// die thermal node, read by ADS1254 channels — bridge outputs, bridge voltages through a divider
// (the sensors' temperature signals) — and an outside-air-temperature RTD probe.
//
// Input per 100 Hz frame (AdsStimulus): static pressure and impact pressure at the unit's ports,
// the air around the board and the air at the OAT probe. Output (AdsRawFrame): the five 24-bit
// codes the unit reports. Frames: none (scalars); units in names.
// Left out: pneumatic lag of the lines (the ADTS model slews the pressures), leaks, the dsPIC's own
// thermometer, channel-to-channel differences between converter channels beyond their noise
// (all five channels share one drawn converter part), divider resistor tempco.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "common/param_reader.h"
#include "sensor_sim/ads1254.h"
#include "sensor_sim/die_thermal.h"
#include "sensor_sim/model_profile.h"
#include "sensor_sim/oat_probe.h"
#include "sensor_sim/pressure_bridge.h"

namespace adahrs::sensor_sim {

struct AdsStimulus {
  double ps_pa = 101325.0;   ///< static pressure at the static port
  double qc_pa = 0.0;        ///< impact pressure: pitot-port pressure minus static
  double air_temp_c = 25.0;  ///< air around the board
  double oat_c = 25.0;       ///< air at the OAT probe
};

struct AdsRawFrame {
  int32_t ps_cnt = 0;       ///< static bridge output
  int32_t pt_cnt = 0;       ///< pitot bridge output
  int32_t ps_temp_cnt = 0;  ///< static bridge voltage through the divider
  int32_t pt_temp_cnt = 0;  ///< pitot bridge voltage through the divider
  int32_t oat_cnt = 0;      ///< OAT divider output
};

struct AdsUnitParams {
  std::string serial = "ADS-0000";
  double frame_period_s = 0.01;
  PressureBridgeParams static_bridge = PressureBridgeParams::Typical(PressureBridgeKind::kAbsolute);
  PressureBridgeParams pitot_bridge =
      PressureBridgeParams::Typical(PressureBridgeKind::kDifferential);
  Ads1254Params adc = Ads1254Params::Typical();
  double bridge_divider_ratio = 0.5;  ///< V_B fraction reaching the converter (keeps it < VREF)
  OatProbeParams oat = OatProbeParams::Typical(RtdElement::kPt1000);
  DieThermalParams static_thermal;
  DieThermalParams pitot_thermal;

  static AdsUnitParams Draw(const std::string& serial, uint64_t seed, ModelProfile profile);
  void ApplyProfile(ModelProfile profile);
  /// kPlayHysteresis puts both bridges on the play-operator law; the other variants leave the ADS
  /// as is.
  void ApplyVariant(TruthVariant variant);
  nlohmann::json ToJson() const;
  static AdsUnitParams FromJson(const common::ParamReader& reader);
};

class AdsUnit {
 public:
  AdsUnit(const AdsUnitParams& params, uint64_t noise_seed, double initial_air_temp_c);

  AdsRawFrame Step(const AdsStimulus& stimulus);

  const AdsUnitParams& params() const { return params_; }
  /// Die temperatures after the last step (truth, for diagnosis).
  double static_die_c() const { return static_die_.die_temp_c(); }
  double pitot_die_c() const { return pitot_die_.die_temp_c(); }

 private:
  AdsUnitParams params_;
  PressureBridge static_bridge_;
  PressureBridge pitot_bridge_;
  Ads1254 ps_adc_, pt_adc_, ps_temp_adc_, pt_temp_adc_, oat_adc_;
  OatProbe oat_;
  DieThermal static_die_;
  DieThermal pitot_die_;
};

}  // namespace adahrs::sensor_sim
