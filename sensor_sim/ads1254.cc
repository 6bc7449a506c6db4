#include "sensor_sim/ads1254.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sensor_sim/fast_math.h"

namespace adahrs::sensor_sim {
namespace {

// 2^23 codes per VREF: +VREF ↔ 0x7FFFFF, −VREF ↔ 0x800000 (SBAS213, two's complement output).
constexpr double kCodesPerFullScale = 8388608.0;
constexpr double kPpm = 1e-6;
constexpr double kUvPerV = 1e6;

// Datasheet and design values (physics.md §3.3).
constexpr double kTypicalVref_v = 4.096;          // datasheet test condition
constexpr double kTypicalNoise_uv_rms = 14.6;     // V, one conversion, VREF 4.096 V, 20 kHz
constexpr int kTypicalAveragingCount = 64;        // design choice of the firmware (E)
constexpr double kMaxInl_ppm_fsr = 15.0;          // V, datasheet maximum
constexpr double kTypicalInl_ppm_fsr = 5.0;       // E: one sigma of the Draw distribution
constexpr double kReferenceTolerance_ppm = 2000;  // E: ±0.2 % initial accuracy of the reference
constexpr int kMaxAveragingCount = 4096;          // 36-bit accumulator limit (physics.md §3.3)

}  // namespace

Ads1254Effects Ads1254Effects::Nominal() {
  return {.noise = true, .inl = false, .reference_error = true};
}

Ads1254Effects Ads1254Effects::All() {
  return {.noise = true, .inl = true, .reference_error = true};
}

Ads1254Params Ads1254Params::Typical() {
  return {.vref_v = kTypicalVref_v,
          .reference_error_ppm = 0.0,
          .noise_uv_rms = kTypicalNoise_uv_rms,
          .averaging_count = kTypicalAveragingCount,
          .inl_ppm_fsr = kTypicalInl_ppm_fsr,
          .effects = Ads1254Effects::Nominal()};
}

Ads1254Params Ads1254Params::Draw(uint64_t seed) {
  common::Rng rng(common::Rng::Derive(seed, 0x1254));
  Ads1254Params p = Typical();
  p.reference_error_ppm = rng.Tolerance(0.0, kReferenceTolerance_ppm);
  p.inl_ppm_fsr = rng.Tolerance(0.0, kMaxInl_ppm_fsr);
  p.effects = Ads1254Effects::All();
  return p;
}

nlohmann::json Ads1254Params::ToJson() const {
  return {{"vref_v", vref_v},
          {"reference_error_ppm", reference_error_ppm},
          {"noise_uv_rms", noise_uv_rms},
          {"averaging_count", averaging_count},
          {"inl_ppm_fsr", inl_ppm_fsr},
          {"effects",
           {{"noise", effects.noise},
            {"inl", effects.inl},
            {"reference_error", effects.reference_error}}}};
}

Ads1254Params Ads1254Params::FromJson(const common::ParamReader& reader) {
  Ads1254Params p;
  p.vref_v = reader.Number("vref_v", 0.5, 5.0, "V");
  p.reference_error_ppm = reader.Number("reference_error_ppm", -10000.0, 10000.0, "ppm");
  p.noise_uv_rms = reader.Number("noise_uv_rms", 0.0, 1000.0, "uV rms");
  p.averaging_count = static_cast<int>(reader.Integer("averaging_count", 1, kMaxAveragingCount));
  p.inl_ppm_fsr = reader.Number("inl_ppm_fsr", -kMaxInl_ppm_fsr, kMaxInl_ppm_fsr, "ppm FSR");
  const common::ParamReader effects = reader.Child("effects");
  p.effects.noise = effects.Flag("noise");
  p.effects.inl = effects.Flag("inl");
  p.effects.reference_error = effects.Flag("reference_error");
  effects.ExpectAllKeysUsed();
  reader.ExpectAllKeysUsed();
  return p;
}

Ads1254::Ads1254(const Ads1254Params& params, uint64_t noise_seed)
    : params_(params), rng_(noise_seed) {
  const Ads1254Effects& on = params_.effects;
  true_vref_v_ =
      params_.vref_v * (1.0 + (on.reference_error ? params_.reference_error_ppm * kPpm : 0.0));
  codes_per_v_ = kCodesPerFullScale / true_vref_v_;
  nominal_lsb_v_ = params_.vref_v / kCodesPerFullScale;
  // Bow a·(1 − (v/VREF)²) with a = INL·FSR: zero at ±VREF, INL at mid-scale.
  inl_peak_v_ = on.inl ? params_.inl_ppm_fsr * kPpm * 2.0 * true_vref_v_ : 0.0;
  inl_per_v2_ = inl_peak_v_ / (true_vref_v_ * true_vref_v_);
  noise_v_rms_ =
      on.noise ? params_.noise_uv_rms / kUvPerV / std::sqrt(double(params_.averaging_count)) : 0.0;
}

int32_t Ads1254::Convert(double input_v) {
  if (!std::isfinite(input_v)) {
    throw std::invalid_argument("Ads1254::Convert: input_v = " + std::to_string(input_v) +
                                " V is not a finite voltage");
  }
  const double z = noise_v_rms_ > 0.0 ? rng_.Normal() : 0.0;  // drawn before the live values
  const double v_clipped = std::clamp(input_v, -true_vref_v_, true_vref_v_);
  double v = input_v + inl_peak_v_ - inl_per_v2_ * v_clipped * v_clipped;
  if (noise_v_rms_ > 0.0) v += noise_v_rms_ * z;
  // Clipping before rounding gives the same code as after (the limits are integers and rounding is
  // monotonic) and keeps the argument inside RoundHalfEven's exact range (it equals nearbyint).
  return static_cast<int32_t>(
      RoundHalfEven(std::clamp(v * codes_per_v_, double(kMinCode), double(kMaxCode))));
}

}  // namespace adahrs::sensor_sim
