// ADXRS150 single-axis yaw-rate gyro (Analog Devices, +-150 deg/s, sensitive axis = package z)
// with the unit's read-out of it: RATEOUT through the output filter into an external 19-bit ADC
// (0..5 V), 16 conversions summed per 100 Hz frame (int32 counts), and the TEMP pin read by the
// dsPIC's 12-bit ADC (0..5 V), 16 conversions summed (uint16 counts, at most 65520).
// Sources: shared/physics.md §2.1-2.2 and §6 rows 1-3, 13; shared/reference-method.md "Scales
// implied" (20,971.52 counts per deg/s = 16 · 2^19/5 V · 12.5 mV/(deg/s)). Full equations,
// parameters with their status tags, and what is left out: docs/models/adxrs150.md.
//
// Model of one frame (each term with its Adxrs150Effects switch in [brackets]):
//   dT    = T_die - 25 degC
//   w_nl  = w + d(w),  d = 150 deg/s · [A·1.5(u^2 - 1/3) + B·2.5(u^3 - 3u/5)] / 100,  u = w/150
//           [nonlinearity]; both shapes are orthogonal to the least-squares line over +-150 deg/s,
//           so sensitivity and null keep their best-fit meaning; max deviation = (|A|+|B|) % FS
//   b     = n1 dT + n2 dT^2 + n3 dT^3 [null_tempco] + G·f_g [g_sensitivity]
//           + k_vs (Vs - 5 V) [supply_sensitivity] + b_BI(t) [bias_instability] + b_RW(t)
//           [rate_random_walk]                                                        (deg/s)
//   V_in  = r · (V_null + S25 · (b + (1 + s1 dT + s2 dT^2) [sensitivity_tempco] · w_nl)),
//           r = Vs / 5 V if output_ratiometric [supply_sensitivity], else 1
//   RATEOUT = one-pole low-pass of (V_in + white noise, one-sided density S25·N [noise]) with
//           tau = R_OUT·C_OUT; V_in is held constant over the frame.
//   The 16 conversions sample RATEOUT at T/16, 2T/16, ..., T within the frame; the sum of their
//   codes is the output (summed_adc.h) [adc_quantization, noise]. The filter state and the frame
//   mean are advanced exactly with a 2x2 Gaussian draw per frame (see adxrs150.cc), so a Step
//   costs two draws, not sixteen.
//   TEMP  = r_T · (V_T298 + k_T · (T_die + 273.15 K - 298.15 K)), r_T as r.
//
// Left out: turn-on transient, self-test, resonator (14 kHz) spikes, vibration rectification,
// cross-axis sensitivity (the unit model applies misalignment), thermal lag (the caller gives die
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
