// One channel of the TI/Burr-Brown ADS1254 24-bit delta-sigma converter (datasheet SBAS213,
// shared/physics.md §3.3 and §6 row 8), as the ADS air-data board reads it: a differential input
// voltage becomes a 24-bit two's complement code, the firmware averaging N consecutive conversions
// per frame, with the reference's error (a gain error to a reader using the nominal vref_v), the
// INL as a symmetric bow zero at ±full scale, and noise falling as 1/√N, clipped to the code range.
// Units: input in V (differential), output the averaged, rounded code as int32_t (sign-extended).
// Equations, parameters and datasheet figures: docs/models/ads1254.md.
// Left out: the converter's own offset and gain error (calibration absorbs them), digital-filter
// settling after a CHSEL change (settled conversions assumed), quantisation of each conversion
// before averaging, noise that changes with VREF, input impedance and source loading, temperature
// drift of the converter.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

#include "common/param_reader.h"
#include "common/random.h"

namespace adahrs::sensor_sim {

/// Separately switchable physical terms of the converter model.
struct Ads1254Effects {
  bool noise = false;            ///< conversion noise, averaged over N conversions
  bool inl = false;              ///< integral-nonlinearity bow
  bool reference_error = false;  ///< true VREF differs from the nominal vref_v

  /// Noise and reference error on; INL off (physics.md §6 row 8: usually left out).
  static Ads1254Effects Nominal();
  /// Every term on.
  static Ads1254Effects All();
  bool operator==(const Ads1254Effects&) const = default;
};

/// One converter channel's parameters.
struct Ads1254Params {
  double vref_v = 0.0;               ///< nominal reference voltage; FSR = ±vref_v
  double reference_error_ppm = 0.0;  ///< (true − nominal)/nominal reference voltage
  double noise_uv_rms = 0.0;         ///< rms noise of one conversion
  int averaging_count = 1;           ///< N conversions averaged per frame
  double inl_ppm_fsr = 0.0;          ///< INL bow at mid-scale, signed, ppm of FSR = 2·VREF
  Ads1254Effects effects;

  /// Datasheet typical part at VREF = 4.096 V, N = 64, every effect per `Nominal()`.
  static Ads1254Params Typical();
  /// One part drawn from the datasheet distributions (deterministic per seed), All() effects.
  static Ads1254Params Draw(uint64_t seed);
  nlohmann::json ToJson() const;
  /// Reads every key with its allowed range; throws ParamError naming the JSON path.
  static Ads1254Params FromJson(const common::ParamReader& reader);
  bool operator==(const Ads1254Params&) const = default;
};

/// One ADS1254 channel: volts in, averaged 24-bit code out.
class Ads1254 {
 public:
  static constexpr int32_t kMaxCode = (1 << 23) - 1;
  static constexpr int32_t kMinCode = -(1 << 23);

  Ads1254(const Ads1254Params& params, uint64_t noise_seed);

  /// One frame: the average of N conversions of the differential input `input_v`, as a code;
  /// inputs beyond ±VREF clip to the end codes. Throws std::invalid_argument for a non-finite
  /// input.
  int32_t Convert(double input_v);

  /// Volts per code as the reader assumes it (nominal vref_v / 2^23).
  double NominalLsbV() const { return nominal_lsb_v_; }
  const Ads1254Params& params() const { return params_; }

 private:
  Ads1254Params params_;
  common::Rng rng_;
  double true_vref_v_;
  double codes_per_v_;
  double nominal_lsb_v_;
  double inl_peak_v_;
  double inl_per_v2_;
  double noise_v_rms_;
};

}  // namespace adahrs::sensor_sim
