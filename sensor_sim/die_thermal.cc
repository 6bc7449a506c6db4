#include "sensor_sim/die_thermal.h"

#include <cmath>
#include <stdexcept>

#include "common/random.h"

namespace adahrs::sensor_sim {

DieThermalParams DieThermalParams::Typical() { return DieThermalParams{}; }

DieThermalParams DieThermalParams::Draw(uint64_t seed) {
  common::Rng rng(seed);
  DieThermalParams p;
  p.tau_s = rng.Tolerance(300.0, 150.0);
  p.self_heating_c = rng.Tolerance(3.0, 2.0);
  return p;
}

nlohmann::json DieThermalParams::ToJson() const {
  return {{"tau_s", tau_s},
          {"self_heating_c", self_heating_c},
          {"effects", {{"lag", effects.lag}, {"self_heating", effects.self_heating}}}};
}

DieThermalParams DieThermalParams::FromJson(const common::ParamReader& reader) {
  DieThermalParams p;
  p.tau_s = reader.Number("tau_s", 1.0, 7200.0, "s");
  p.self_heating_c = reader.Number("self_heating_c", 0.0, 30.0, "degC");
  const common::ParamReader effects = reader.Child("effects");
  p.effects.lag = effects.Flag("lag");
  p.effects.self_heating = effects.Flag("self_heating");
  effects.ExpectAllKeysUsed();
  reader.ExpectAllKeysUsed();
  return p;
}

DieThermal::DieThermal(const DieThermalParams& params, double step_s, double initial_air_temp_c)
    : params_(params),
      decay_(params.effects.lag ? std::exp(-step_s / params.tau_s) : 0.0),
      die_temp_c_(initial_air_temp_c) {
  if (!(step_s > 0.0)) throw std::invalid_argument("DieThermal: step_s must be positive");
}

void DieThermal::Hold(double air_temp_c, double duration_s) {
  const double target_c =
      air_temp_c + (params_.effects.self_heating ? params_.self_heating_c : 0.0);
  const double decay = params_.effects.lag ? std::exp(-duration_s / params_.tau_s) : 0.0;
  die_temp_c_ = target_c + (die_temp_c_ - target_c) * decay;
}

}  // namespace adahrs::sensor_sim
