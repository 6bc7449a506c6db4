#include "sensor_sim/ads_unit.h"

#include "common/random.h"

namespace adahrs::sensor_sim {
namespace {

enum Stream : uint64_t {
  kStaticBridge = 0,
  kPitotBridge,
  kAdc,
  kOat,
  kStaticThermal,
  kPitotThermal,
  kDivider,
  kNoiseStatic = 100,
  kNoisePitot,
  kNoiseAdc,  // + channel
};

}  // namespace

AdsUnitParams AdsUnitParams::Draw(const std::string& serial, uint64_t seed, ModelProfile profile) {
  AdsUnitParams p;
  p.serial = serial;
  p.static_bridge = PressureBridgeParams::Draw(PressureBridgeKind::kAbsolute,
                                               common::Rng::Derive(seed, kStaticBridge));
  p.pitot_bridge = PressureBridgeParams::Draw(PressureBridgeKind::kDifferential,
                                              common::Rng::Derive(seed, kPitotBridge));
  p.adc = Ads1254Params::Draw(common::Rng::Derive(seed, kAdc));
  p.oat = OatProbeParams::Draw(RtdElement::kPt1000, common::Rng::Derive(seed, kOat));
  p.static_thermal = DieThermalParams::Draw(common::Rng::Derive(seed, kStaticThermal));
  p.pitot_thermal = DieThermalParams::Draw(common::Rng::Derive(seed, kPitotThermal));
  // A 0.1 % resistor pair: the ratio is within ±0.2 % (E).
  common::Rng divider(common::Rng::Derive(seed, kDivider));
  p.bridge_divider_ratio = divider.Tolerance(0.5, 0.001);
  p.ApplyProfile(profile);
  return p;
}

void AdsUnitParams::ApplyProfile(ModelProfile profile) {
  static_bridge.effects = EffectsFor<PressureBridgeEffects>(profile);
  pitot_bridge.effects = EffectsFor<PressureBridgeEffects>(profile);
  adc.effects = EffectsFor<Ads1254Effects>(profile);
  oat.effects = EffectsFor<OatProbeEffects>(profile);
  static_thermal.effects = EffectsFor<DieThermalEffects>(profile);
  pitot_thermal.effects = EffectsFor<DieThermalEffects>(profile);
}

void AdsUnitParams::ApplyVariant(TruthVariant variant) {
  const HysteresisLaw law = variant == TruthVariant::kPlayHysteresis
                                ? HysteresisLaw::kPlayOperators
                                : HysteresisLaw::kTravelPreisach;
  static_bridge.hysteresis_law = law;
  pitot_bridge.hysteresis_law = law;
}

nlohmann::json AdsUnitParams::ToJson() const {
  return {{"serial", serial},
          {"frame_period_s", frame_period_s},
          {"static_bridge", static_bridge.ToJson()},
          {"pitot_bridge", pitot_bridge.ToJson()},
          {"adc", adc.ToJson()},
          {"bridge_divider_ratio", bridge_divider_ratio},
          {"oat", oat.ToJson()},
          {"static_thermal", static_thermal.ToJson()},
          {"pitot_thermal", pitot_thermal.ToJson()}};
}

AdsUnitParams AdsUnitParams::FromJson(const common::ParamReader& reader) {
  AdsUnitParams p;
  p.serial = reader.String("serial");
  p.frame_period_s = reader.Number("frame_period_s", 0.001, 1.0, "s");
  p.static_bridge = PressureBridgeParams::FromJson(reader.Child("static_bridge"));
  p.pitot_bridge = PressureBridgeParams::FromJson(reader.Child("pitot_bridge"));
  p.adc = Ads1254Params::FromJson(reader.Child("adc"));
  p.bridge_divider_ratio = reader.Number("bridge_divider_ratio", 0.05, 1.0, "ratio");
  p.oat = OatProbeParams::FromJson(reader.Child("oat"));
  p.static_thermal = DieThermalParams::FromJson(reader.Child("static_thermal"));
  p.pitot_thermal = DieThermalParams::FromJson(reader.Child("pitot_thermal"));
  reader.ExpectAllKeysUsed();
  return p;
}

AdsUnit::AdsUnit(const AdsUnitParams& params, uint64_t noise_seed, double initial_air_temp_c)
    : params_(params),
      static_bridge_(params.static_bridge, common::Rng::Derive(noise_seed, kNoiseStatic)),
      pitot_bridge_(params.pitot_bridge, common::Rng::Derive(noise_seed, kNoisePitot)),
      ps_adc_(params.adc, common::Rng::Derive(noise_seed, kNoiseAdc + 0)),
      pt_adc_(params.adc, common::Rng::Derive(noise_seed, kNoiseAdc + 1)),
      ps_temp_adc_(params.adc, common::Rng::Derive(noise_seed, kNoiseAdc + 2)),
      pt_temp_adc_(params.adc, common::Rng::Derive(noise_seed, kNoiseAdc + 3)),
      oat_adc_(params.adc, common::Rng::Derive(noise_seed, kNoiseAdc + 4)),
      oat_(params.oat),
      static_die_(params.static_thermal, params.frame_period_s, initial_air_temp_c),
      pitot_die_(params.pitot_thermal, params.frame_period_s, initial_air_temp_c) {}

AdsRawFrame AdsUnit::Step(const AdsStimulus& s) {
  const double static_die_c = static_die_.Step(s.air_temp_c);
  const double pitot_die_c = pitot_die_.Step(s.air_temp_c);
  const PressureBridgeOutput ps = static_bridge_.Step({s.ps_pa, static_die_c});
  const PressureBridgeOutput pt = pitot_bridge_.Step({s.qc_pa, pitot_die_c});
  AdsRawFrame f;
  f.ps_cnt = ps_adc_.Convert(ps.signal_v);
  f.pt_cnt = pt_adc_.Convert(pt.signal_v);
  f.ps_temp_cnt = ps_temp_adc_.Convert(ps.bridge_v * params_.bridge_divider_ratio);
  f.pt_temp_cnt = pt_temp_adc_.Convert(pt.bridge_v * params_.bridge_divider_ratio);
  f.oat_cnt = oat_adc_.Convert(oat_.SignalV(s.oat_c));
  return f;
}

}  // namespace adahrs::sensor_sim
