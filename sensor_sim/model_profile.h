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

/// Sets `effects` to the profile's set: Effects::Nominal() or Effects::All().
template <typename Effects>
Effects EffectsFor(ModelProfile profile) {
  return profile == ModelProfile::kNominal ? Effects::Nominal() : Effects::All();
}

}  // namespace adahrs::sensor_sim
