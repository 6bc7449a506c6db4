// Parameters of one ADXRS150 yaw-rate gyro (Analog Devices, +-150 deg/s) with its read-out, and
// the switches of the physical terms the model includes. Numbers and their status tags
// (V verified, R recalled, D derived, E estimate) come from shared/physics.md §2 and §6; every
// parameter with its source is listed in docs/models/adxrs150.md. R and E numbers are parameters of
// the model, never limits of a test beyond what the datasheet says.
//
// Conventions: "rate-equivalent" offsets (null tempco, g- and supply sensitivity) are in deg/s at
// the input, converted to volts with the unit's sensitivity at 25 degC, so they do not change with
// the sensitivity tempco. Temperatures are the die temperature in degC, the reference is 25 degC.
#pragma once

#include <array>
#include <cstdint>

#include <nlohmann/json.hpp>

#include "common/param_reader.h"

namespace adahrs::sensor_sim {

/// One switch per separately modelled physical term of the ADXRS150 model.
struct Adxrs150Effects {
  bool noise = true;                ///< white rate noise + rate and TEMP ADC noise
  bool bias_instability = true;     ///< 1/f bias floor (Gauss-Markov sum), gyro_bias_process.h
  bool rate_random_walk = false;    ///< random walk of the bias
  bool null_tempco = true;          ///< null drift, cubic in (T - 25 degC)
  bool sensitivity_tempco = false;  ///< sensitivity drift, quadratic in (T - 25 degC)
  bool nonlinearity = true;         ///< scale-factor nonlinearity (quadratic + cubic shapes)
  bool g_sensitivity = false;       ///< rate offset linear in specific force (3-vector)
  bool supply_sensitivity = false;  ///< null vs supply; with output_ratiometric, ratiometry
  bool adc_quantization = true;     ///< per-conversion rounding of both ADCs

  /// What the reference calibration (2007 thesis) assumes: its thermal null fit, offset/scale,
  /// scale-factor nonlinearity, run-time bias-drift filter; noise on. Off: sensitivity tempco (its
  /// future work), g-sensitivity and supply (not in the method), rate random walk.
  static Adxrs150Effects Nominal() { return Adxrs150Effects{}; }
  /// Every term on: the "truth" model.
  static Adxrs150Effects All();

  bool operator==(const Adxrs150Effects&) const = default;
};

/// One unit's parameters. Each quantity carries its unit in its name.
struct Adxrs150Params {
  double sensitivity_mv_per_dps;         ///< at 25 degC, 5 V
  double null_v;                         ///< zero-rate output at 25 degC, 5 V
  bool output_ratiometric;               ///< rate, null and TEMP scale with supply_v / 5 V
  double null_tc1_dps_per_c;             ///< null drift, 1st order in (T - 25)
  double null_tc2_dps_per_c2;            ///< 2nd order
  double null_tc3_dps_per_c3;            ///< 3rd order
  double sensitivity_tc1_ppm_per_c;      ///< sensitivity drift, 1st order
  double sensitivity_tc2_ppm_per_c2;     ///< 2nd order
  double nonlinearity_quadratic_pct_fs;  ///< amplitude of the quadratic shape, % of 150 deg/s
  double nonlinearity_cubic_pct_fs;      ///< amplitude of the cubic shape, % of 150 deg/s
  std::array<double, 3> g_sensitivity_dps_per_g;  ///< along package x, y, z
  double null_supply_dps_per_v;                   ///< null change per volt of supply above 5 V
  double rate_noise_dps_per_rthz;                 ///< one-sided white rate noise density
  double output_filter_r_kohm;                    ///< on-chip R_OUT
  double output_filter_c_nf;                      ///< external C_OUT
  double bias_instability_dph;                    ///< Allan-deviation floor, deg/h
  double rate_random_walk_dph_per_rth;            ///< K, deg/h/sqrt(h)
  double bias_correlation_time_scale = 1.0;       ///< multiplies the flicker poles' times
  double rate_adc_noise_lsb;                      ///< 19-bit ADC noise per conversion, LSB rms
  double temp_out_v_at_298k;                      ///< TEMP pin at 298.15 K
  double temp_out_mv_per_k;                       ///< TEMP pin slope
  double temp_adc_noise_lsb;                      ///< dsPIC 12-bit ADC noise per conv., LSB rms
  Adxrs150Effects effects;

  /// The datasheet typical part (effects Nominal()).
  static Adxrs150Params Typical();
  /// One unit drawn from the datasheet / estimated spreads, deterministic per seed (effects
  /// Nominal()).
  static Adxrs150Params Draw(uint64_t seed);

  nlohmann::json ToJson() const;
  /// Reads every key with its allowed range and unit; refuses unknown keys.
  static Adxrs150Params FromJson(const common::ParamReader& reader);

  bool operator==(const Adxrs150Params&) const = default;
};

}  // namespace adahrs::sensor_sim
