#include "sensor_sim/imu_unit.h"

#include <string>

#include "common/random.h"
#include "sensor_sim/make_array.h"

namespace adahrs::sensor_sim {
namespace {

// Stream ids for Rng::Derive: one per drawn part, so adding a part never shifts another's draw.
enum Stream : uint64_t {
  kAccelChip = 0,  // + chip index
  kGyro = 10,      // + gyro index
  kGeometry = 20,
  kAccelThermal = 30,  // + chip index
  kGyroThermal = 40,   // + gyro index
  kNoiseAccel = 100,   // + chip index
  kNoiseGyro = 110,    // + gyro index
};

template <typename Params, size_t N>
nlohmann::json ArrayJson(const std::array<Params, N>& items) {
  nlohmann::json out = nlohmann::json::array();
  for (const Params& p : items) out.push_back(p.ToJson());
  return out;
}

// Reads a JSON array of exactly N objects, each through Params::FromJson with its own path.
template <typename Params, size_t N>
std::array<Params, N> ArrayFromJson(const common::ParamReader& reader, const char* key) {
  std::array<Params, N> out;
  for (size_t i = 0; i < N; ++i) {
    out[i] = Params::FromJson(reader.Element(key, i, N));
  }
  return out;
}

}  // namespace

ImuUnitParams ImuUnitParams::Draw(const std::string& serial, uint64_t seed, ModelProfile profile) {
  ImuUnitParams p;
  p.serial = serial;
  for (int k = 0; k < 3; ++k) {
    p.accel_chips[k] = Adxl210eParams::Draw(common::Rng::Derive(seed, kAccelChip + k));
    p.gyros[k] = Adxrs150Params::Draw(common::Rng::Derive(seed, kGyro + k));
    p.accel_thermal[k] = DieThermalParams::Draw(common::Rng::Derive(seed, kAccelThermal + k));
    p.gyro_thermal[k] = DieThermalParams::Draw(common::Rng::Derive(seed, kGyroThermal + k));
  }
  p.geometry = Im3Geometry::Draw(common::Rng::Derive(seed, kGeometry));
  p.ApplyProfile(profile);
  return p;
}

void ImuUnitParams::ApplyVariant(TruthVariant variant) {
  if (variant != TruthVariant::kSlowBiasWander) return;
  constexpr double kSlowerPoles = 10.0, kStrongerWalk = 3.0;  // the variant's definition (E)
  for (Adxrs150Params& g : gyros) {
    g.bias_correlation_time_scale = kSlowerPoles;
    g.rate_random_walk_dph_per_rth *= kStrongerWalk;
    g.effects.rate_random_walk = true;
  }
}

void ImuUnitParams::ApplyProfile(ModelProfile profile) {
  for (int k = 0; k < 3; ++k) {
    accel_chips[k].effects = EffectsFor<Adxl210eEffects>(profile);
    gyros[k].effects = EffectsFor<Adxrs150Effects>(profile);
    accel_thermal[k].effects = EffectsFor<DieThermalEffects>(profile);
    gyro_thermal[k].effects = EffectsFor<DieThermalEffects>(profile);
  }
  geometry.misalignment = true;  // mounting misalignment is what cross-axis calibration removes
}

nlohmann::json ImuUnitParams::ToJson() const {
  return {{"serial", serial},
          {"frame_period_s", frame_period_s},
          {"accel_chips", ArrayJson(accel_chips)},
          {"gyros", ArrayJson(gyros)},
          {"geometry", geometry.ToJson()},
          {"accel_thermal", ArrayJson(accel_thermal)},
          {"gyro_thermal", ArrayJson(gyro_thermal)}};
}

ImuUnitParams ImuUnitParams::FromJson(const common::ParamReader& reader) {
  ImuUnitParams p;
  p.serial = reader.String("serial");
  p.frame_period_s = reader.Number("frame_period_s", 0.001, 1.0, "s");
  p.accel_chips = ArrayFromJson<Adxl210eParams, 3>(reader, "accel_chips");
  p.gyros = ArrayFromJson<Adxrs150Params, 3>(reader, "gyros");
  p.geometry = Im3Geometry::FromJson(reader.Child("geometry"));
  p.accel_thermal = ArrayFromJson<DieThermalParams, 3>(reader, "accel_thermal");
  p.gyro_thermal = ArrayFromJson<DieThermalParams, 3>(reader, "gyro_thermal");
  reader.ExpectAllKeysUsed();
  return p;
}

ImuUnit::ImuUnit(const ImuUnitParams& params, uint64_t noise_seed, double initial_air_temp_c)
    : params_(params),
      R_CB_(MakeArray<3>([&](int k) { return params.geometry.R_CB(k); })),
      R_GB_(MakeArray<3>([&](int k) { return params.geometry.R_GB(k); })),
      chips_(MakeArray<3>([&](int k) {
        return Adxl210e(params.accel_chips[k],
                        common::Rng::Derive(noise_seed, kNoiseAccel + k),
                        params.frame_period_s);
      })),
      gyros_(MakeArray<3>([&](int k) {
        return Adxrs150(params.gyros[k],
                        common::Rng::Derive(noise_seed, kNoiseGyro + k),
                        params.frame_period_s);
      })),
      accel_die_(MakeArray<3>([&](int k) {
        return DieThermal(params.accel_thermal[k], params.frame_period_s, initial_air_temp_c);
      })),
      gyro_die_(MakeArray<3>([&](int k) {
        return DieThermal(params.gyro_thermal[k], params.frame_period_s, initial_air_temp_c);
      })) {}

ImuRawFrame ImuUnit::Step(const ImuStimulus& s) {
  ImuRawFrame frame;
  std::array<Adxl210eInput, 3> chip_inputs;
  for (int k = 0; k < 3; ++k) {
    die_.accel_chip_c[k] = accel_die_[k].Step(s.air_temp_c);
    const Eigen::Vector3d f_C_g = R_CB_[k] * s.f_B_g;
    chip_inputs[k] = {f_C_g.x(), f_C_g.y(), f_C_g.z(), die_.accel_chip_c[k], s.supply_v};
  }
  std::array<Adxl210eOutput, 3> chip_outputs;
  Adxl210e::StepEach(chips_, chip_inputs, chip_outputs);
  for (int k = 0; k < 3; ++k) {
    frame.accel[2 * k] = chip_outputs[k].x;
    frame.accel[2 * k + 1] = chip_outputs[k].y;
  }
  for (int g = 0; g < 3; ++g) {
    die_.gyro_c[g] = gyro_die_[g].Step(s.air_temp_c);
    const Eigen::Vector3d w_G_dps = R_GB_[g] * s.w_B_dps;
    const Eigen::Vector3d f_G_g = R_GB_[g] * s.f_B_g;
    const Adxrs150Output out = gyros_[g].Step(
        Adxrs150Input{w_G_dps.z(), f_G_g.x(), f_G_g.y(), f_G_g.z(), die_.gyro_c[g], s.supply_v});
    frame.gyro_cnt[g] = out.rate_cnt;
    frame.temp_cnt[g] = out.temp_cnt;
  }
  return frame;
}

void ImuUnit::SoakWithoutFrames(double air_temp_c, double duration_s) {
  for (int k = 0; k < 3; ++k) {
    accel_die_[k].Hold(air_temp_c, duration_s);
    die_.accel_chip_c[k] = accel_die_[k].die_temp_c();
    gyro_die_[k].Hold(air_temp_c, duration_s);
    die_.gyro_c[k] = gyro_die_[k].die_temp_c();
  }
}

}  // namespace adahrs::sensor_sim
