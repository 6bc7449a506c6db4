// ADXRS150 single-axis yaw-rate gyro (Analog Devices, ±150 deg/s, sensitive axis = package z)
// with the unit's read-out of it: RATEOUT through the output filter into an external 19-bit ADC
// (0..5 V), 16 conversions summed per 100 Hz frame (int32 counts, 20,971.52 counts per deg/s),
// and the TEMP pin read by the dsPIC's 12-bit ADC (0..5 V), 16 conversions summed (uint16 counts,
// at most 65520). Per frame: span nonlinearity orthogonal to the best-fit line, null tempco,
// g-sensitivity, supply sensitivity, bias instability and rate random walk (gyro_bias_process.h),
// sensitivity tempco, white noise through the one-pole filter, summed conversions (summed_adc.h),
// each term with its Adxrs150Effects switch; filter state and frame mean advanced exactly with
// two Gaussian draws per frame.
// Frames and units: gyro package frame G (z_G sensitive); rate in deg/s, die temperature in degC,
// supply in V, g-sensitivity input in g; outputs in counts (_cnt).
// Equations, parameters with status tags, sources: docs/models/adxrs150.md.
// Left out: turn-on transient, self-test, resonator spikes, vibration rectification, cross-axis
// sensitivity (the unit model applies misalignment), thermal lag (the caller gives the die
// temperature), thermal hysteresis, amplifier swing limits inside the ADC range, ADC linearity.
#pragma once

#include <cstdint>

#include "common/random.h"
#include "sensor_sim/adxrs150_params.h"
#include "sensor_sim/gyro_bias_process.h"
#include "sensor_sim/summed_adc.h"

namespace adahrs::sensor_sim {

/// Inputs for one frame, held constant over the frame.
struct Adxrs150Input {
  double w_dps;                ///< angular rate about the gyro's sensitive axis (package z), deg/s
  double f_x_g, f_y_g, f_z_g;  ///< specific force in the gyro package frame, g
  double die_temp_c;           ///< die temperature, degC
  double supply_v;             ///< supply voltage, nominal 5 V
};

/// Raw outputs of one frame.
struct Adxrs150Output {
  int32_t rate_cnt;   ///< sum of 16 conversions of the 19-bit rate ADC
  uint16_t temp_cnt;  ///< sum of 16 conversions of the 12-bit TEMP ADC
};

class Adxrs150 {
 public:
  static constexpr double kFullScale_dps = 150.0;  // V [RS150P]
  static constexpr double kReferenceTemp_c = 25.0;
  static constexpr double kNominalSupply_v = 5.0;        // V [RS150P]
  static constexpr double kTempOutReference_k = 298.15;  // R, "2.50 V at 298 K"
  static constexpr int kConversionsPerFrame = 16;        // reference-method.md
  static constexpr int kRateAdcBits = 19;
  static constexpr int kTempAdcBits = 12;
  static constexpr double kAdcFullScale_v = 5.0;

  /// `frame_period_s` is the unit's frame period (0.01 s at 100 Hz). Noise streams are derived
  /// from `noise_seed`; the same params, seed and inputs give the same outputs. Throws
  /// std::invalid_argument if `frame_period_s` is not positive. `params` are taken as valid (read
  /// them with FromJson for range checks).
  Adxrs150(const Adxrs150Params& params, uint64_t noise_seed, double frame_period_s);

  /// Advances one frame and returns its raw outputs. No allocation.
  Adxrs150Output Step(const Adxrs150Input& input);

  const Adxrs150Params& params() const { return params_; }
  /// Truth: rate counts per deg/s at 25 degC and 5 V (best-fit slope).
  double RateCountsPerDps() const;
  /// Truth: rate counts at zero rate, 25 degC, 5 V, 0 g, no stochastic bias (best-fit intercept).
  double NullCounts() const;
  /// Output filter -3 dB frequency, Hz.
  double OutputFilterCutoff_hz() const;

 private:
  Adxrs150Params params_;
  // Precomputed coefficients; a coefficient of a disabled effect is zero.
  double s25_v_per_dps_;
  double null_tc_dps_[3];
  double sens_tc_per_c_[2];
  double nonlinearity_[4];  // d(w) = sum nonlinearity_[k] · w^k
  double g_sens_dps_per_g_[3];
  double null_supply_dps_per_v_;
  double ratio_per_v_;  // r = 1 + ratio_per_v_ · (Vs - 5 V)
  double temp_out_v_per_k_;
  // Output filter over one frame: x_end = a16 x + (1 - a16) u + w1; y = beta x + (1 - beta) u + w2.
  double a16_;
  double beta_;
  double l11_v_, l21_v_, l22_v_;  // Cholesky factor of cov(w1, w2)
  double stationary_sigma_v_;
  double filter_state_v_ = 0.0;
  bool started_ = false;
  bool noise_on_;
  double temp_noise_sigma_v_;
  SummedAdc rate_adc_;
  SummedAdc temp_adc_;
  GyroBiasProcess bias_;
  common::Rng rate_rng_;
  common::Rng temp_rng_;
};

}  // namespace adahrs::sensor_sim
