// Which physical terms a simulated unit carries. A calibration engineer's "nominal" model holds the
// terms the reference method compensates; the "truth" model has every modelled effect on. The two
// differ only by named effects, which is what discrepancy diagnosis later works with.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace adahrs::sensor_sim {

enum class ModelProfile { kNominal, kTruth };

inline std::string ToString(ModelProfile profile) {
  return profile == ModelProfile::kNominal ? "nominal" : "truth";
}

inline ModelProfile ModelProfileFromString(std::string_view name) {
  if (name == "nominal") return ModelProfile::kNominal;
  if (name == "truth") return ModelProfile::kTruth;
  throw std::invalid_argument("unknown model profile '" + std::string(name) +
                              "' (expected nominal or truth)");
}

/// Truth variants in model form (docs/sensor-models.md "Truth variants"): the same effects as the
/// truth profile, with a law of another form than the calibration's own where that law is an
/// engineering estimate. kStandard: the pressure bridges follow the travel Preisach law (spans
/// drawn per part), the gyro bias wander has its datasheet form. kPlayHysteresis: the bridges
/// follow the play-operator law (play_hysteresis.h). kSlowBiasWander: every gyro's
/// flicker poles have ten times the correlation times (the Allan floor over 10...5,000 s kept)
/// and its rate random walk is on at three times the drawn one.
enum class TruthVariant { kStandard, kPlayHysteresis, kSlowBiasWander };

inline std::string ToString(TruthVariant variant) {
  switch (variant) {
    case TruthVariant::kPlayHysteresis:
      return "play_hysteresis";
    case TruthVariant::kSlowBiasWander:
      return "slow_bias_wander";
    case TruthVariant::kStandard:
      break;
  }
  return "standard";
}

/// One sentence for summaries: what the variant's truth is, beside the calibration's own models.
inline std::string Describe(TruthVariant variant) {
  switch (variant) {
    case TruthVariant::kPlayHysteresis:
      return "pressure bridges on the play-operator hysteresis law (another family than the "
             "calibration's travel law), spans drawn per bridge";
    case TruthVariant::kSlowBiasWander:
      return "gyro bias wander ten times slower than the datasheet form, rate random walk on at "
             "three times the drawn one";
    case TruthVariant::kStandard:
      break;
  }
  return "travel-law hysteresis with spans drawn per bridge, gyro bias wander of the datasheet "
         "form";
}

inline TruthVariant TruthVariantFromString(std::string_view name) {
  for (TruthVariant v :
       {TruthVariant::kStandard, TruthVariant::kPlayHysteresis, TruthVariant::kSlowBiasWander}) {
    if (name == ToString(v)) return v;
  }
  throw std::invalid_argument("unknown truth variant '" + std::string(name) +
                              "' (expected standard, play_hysteresis or slow_bias_wander)");
}

/// Sets `effects` to the profile's set: Effects::Nominal() or Effects::All().
template <typename Effects>
Effects EffectsFor(ModelProfile profile) {
  return profile == ModelProfile::kNominal ? Effects::Nominal() : Effects::All();
}

}  // namespace adahrs::sensor_sim
