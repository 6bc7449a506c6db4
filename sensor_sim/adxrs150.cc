#include "sensor_sim/adxrs150.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/units.h"

namespace adahrs::sensor_sim {
namespace {

// Named conversions not (yet) in units.h.
constexpr double kVoltsPerMillivolt = 1e-3;
constexpr double kPerPpm = 1e-6;
constexpr double kPerPercent = 1e-2;
constexpr double kOhmsPerKiloohm = 1e3;
constexpr double kFaradsPerNanofarad = 1e-9;
constexpr double kSecondsPerHour = 3600.0;
constexpr double kDpsPerDph = 1.0 / kSecondsPerHour;
// deg/h/sqrt(h) -> deg/s/sqrt(s): divide by 3600 (deg/h -> deg/s) and by 60 (sqrt(h) -> sqrt(s)).
constexpr double kDpsPerRtsPerDphPerRth = 1.0 / (kSecondsPerHour * 60.0);

// Noise streams of one gyro, derived from its noise seed.
constexpr uint64_t kRateNoiseStream = 0;
constexpr uint64_t kTempNoiseStream = 1;
constexpr uint64_t kBiasProcessStream = 2;

}  // namespace

Adxrs150::Adxrs150(const Adxrs150Params& params, uint64_t noise_seed, double frame_period_s)
    : params_(params),
      s25_v_per_dps_(params.sensitivity_mv_per_dps * kVoltsPerMillivolt),
      noise_on_(params.effects.noise),
      rate_adc_(kRateAdcBits,
                kAdcFullScale_v,
                kConversionsPerFrame,
                params.rate_adc_noise_lsb,
                params.effects.noise,
                params.effects.adc_quantization),
      temp_adc_(kTempAdcBits,
                kAdcFullScale_v,
                kConversionsPerFrame,
                params.temp_adc_noise_lsb,
                params.effects.noise,
                params.effects.adc_quantization),
      bias_(params.bias_instability_dph * kDpsPerDph,
            params.effects.bias_instability,
            params.rate_random_walk_dph_per_rth * kDpsPerRtsPerDphPerRth,
            params.effects.rate_random_walk,
            frame_period_s,
            common::Rng::Derive(noise_seed, kBiasProcessStream),
            params.bias_correlation_time_scale),
      rate_rng_(common::Rng::Derive(noise_seed, kRateNoiseStream)),
      temp_rng_(common::Rng::Derive(noise_seed, kTempNoiseStream)) {
  if (!(frame_period_s > 0.0) || !std::isfinite(frame_period_s)) {
    throw std::invalid_argument("Adxrs150: frame_period_s must be positive and finite, got " +
                                std::to_string(frame_period_s));
  }
  const Adxrs150Effects& e = params.effects;
  const bool tc = e.null_tempco;
  null_tc_dps_[0] = tc ? params.null_tc1_dps_per_c : 0.0;
  null_tc_dps_[1] = tc ? params.null_tc2_dps_per_c2 : 0.0;
  null_tc_dps_[2] = tc ? params.null_tc3_dps_per_c3 : 0.0;
  sens_tc_per_c_[0] = e.sensitivity_tempco ? params.sensitivity_tc1_ppm_per_c * kPerPpm : 0.0;
  sens_tc_per_c_[1] = e.sensitivity_tempco ? params.sensitivity_tc2_ppm_per_c2 * kPerPpm : 0.0;

  // Nonlinearity d(w) = FS · [A·1.5(u^2 - 1/3) + B·2.5(u^3 - 3u/5)], u = w/FS, A and B as
  // fractions. q(u) = u^2 - 1/3 and c(u) = u^3 - 3u/5 are orthogonal to 1 and u on [-1, 1] (so the
  // least-squares line of w + d(w) is w itself); max|q| = 2/3 and max|c| = 2/5, both at u = +-1,
  // where A·1.5q + B·2.5c = A +- B, so max|d| = (|A| + |B|)·FS. Expanded in powers of w:
  //   d0 = -A·FS/2,  d1 = -3B/2,  d2 = 3A/(2 FS),  d3 = 5B/(2 FS^2).
  const double a = e.nonlinearity ? params.nonlinearity_quadratic_pct_fs * kPerPercent : 0.0;
  const double b = e.nonlinearity ? params.nonlinearity_cubic_pct_fs * kPerPercent : 0.0;
  nonlinearity_[0] = -0.5 * a * kFullScale_dps;
  nonlinearity_[1] = -1.5 * b;
  nonlinearity_[2] = 1.5 * a / kFullScale_dps;
  nonlinearity_[3] = 2.5 * b / (kFullScale_dps * kFullScale_dps);

  for (int i = 0; i < 3; ++i) {
    g_sens_dps_per_g_[i] = e.g_sensitivity ? params.g_sensitivity_dps_per_g[i] : 0.0;
  }
  null_supply_dps_per_v_ = e.supply_sensitivity ? params.null_supply_dps_per_v : 0.0;
  ratio_per_v_ = (e.supply_sensitivity && params.output_ratiometric) ? 1.0 / kNominalSupply_v : 0.0;
  temp_out_v_per_k_ = params.temp_out_mv_per_k * kVoltsPerMillivolt;

  // Output filter and the frame's 16 conversions.
  // RATEOUT x(t) obeys tau dx/dt = u - x + noise. With conversions every D = T/16 and
  // a = exp(-D/tau), the exact discrete form between conversions is
  //   x_i = a x_{i-1} + (1 - a) u + e_i,  var(e_i) = sx^2 (1 - a^2),
  // where sx^2 = S1 / (4 tau) is the stationary variance of white noise of one-sided density S1
  // through the pole (integral of S1/(1 + (2 pi f tau)^2) over f >= 0). Summing over a frame:
  //   x_16 = a^16 x_0 + (1 - a^16) u + sum_i a^(16-i) e_i                       =: ... + w1
  //   y = (1/16) sum_j x_j = beta x_0 + (1 - beta) u + sum_i c_i e_i,          =: ... + w2
  //   beta = (1/16) sum_{j=1..16} a^j,  c_i = (1/16) sum_{j=i..16} a^(j-i).
  // (w1, w2) is zero-mean Gaussian with covariance var(e)·[sum d^2, sum d c; sum d c, sum c^2]
  // (d_i = a^(16-i)); the ADC adds its own variance to w2. One Cholesky-factored pair per frame.
  const double tau_s = params.output_filter_r_kohm * kOhmsPerKiloohm * params.output_filter_c_nf *
                       kFaradsPerNanofarad;
  const int n = kConversionsPerFrame;
  const double d_s = frame_period_s / n;
  const double a_step = std::exp(-d_s / tau_s);
  a16_ = std::pow(a_step, n);
  double beta_sum = 0.0;
  for (int j = 1; j <= n; ++j) beta_sum += std::pow(a_step, j);
  beta_ = beta_sum / n;
  const double density_v_per_rthz = e.noise ? params.rate_noise_dps_per_rthz * s25_v_per_dps_ : 0.0;
  const double stationary_var_v2 = density_v_per_rthz * density_v_per_rthz / (4.0 * tau_s);
  stationary_sigma_v_ = std::sqrt(stationary_var_v2);
  const double e_var_v2 = stationary_var_v2 * (1.0 - a_step * a_step);
  double s11 = 0.0, s12 = 0.0, s22 = 0.0;
  for (int i = 1; i <= n; ++i) {
    const double d = std::pow(a_step, n - i);
    double c = 0.0;
    for (int j = i; j <= n; ++j) c += std::pow(a_step, j - i);
    c /= n;
    s11 += d * d;
    s12 += d * c;
    s22 += c * c;
  }
  s11 *= e_var_v2;
  s12 *= e_var_v2;
  s22 = s22 * e_var_v2 + rate_adc_.MeanNoiseVariance_v2();
  l11_v_ = std::sqrt(s11);
  l21_v_ = l11_v_ > 0.0 ? s12 / l11_v_ : 0.0;
  l22_v_ = std::sqrt(std::max(0.0, s22 - l21_v_ * l21_v_));
  temp_noise_sigma_v_ = std::sqrt(temp_adc_.MeanNoiseVariance_v2());
}

Adxrs150Output Adxrs150::Step(const Adxrs150Input& in) {
  // The frame's Gaussian draws come first, while little else is live: a draw's rare slow path
  // calls libm, and values live across it would be saved and restored around every draw.
  double z1 = 0.0, z2 = 0.0, z_temp = 0.0;
  if (noise_on_) {
    const std::array<double, 2> z_rate = rate_rng_.NormalPair();
    z1 = z_rate[0];
    z2 = z_rate[1];
    z_temp = temp_rng_.Normal();
  }
  const double bias_process_dps = bias_.Step();

  const double dt_c = in.die_temp_c - kReferenceTemp_c;
  const double dvs_v = in.supply_v - kNominalSupply_v;
  const double w = in.w_dps;

  const double bias_dps =
      dt_c * (null_tc_dps_[0] + dt_c * (null_tc_dps_[1] + dt_c * null_tc_dps_[2])) +
      g_sens_dps_per_g_[0] * in.f_x_g + g_sens_dps_per_g_[1] * in.f_y_g +
      g_sens_dps_per_g_[2] * in.f_z_g + null_supply_dps_per_v_ * dvs_v + bias_process_dps;
  const double w_nl_dps =
      w + nonlinearity_[0] + w * (nonlinearity_[1] + w * (nonlinearity_[2] + w * nonlinearity_[3]));
  const double gain = 1.0 + dt_c * (sens_tc_per_c_[0] + dt_c * sens_tc_per_c_[1]);
  const double ratio = 1.0 + ratio_per_v_ * dvs_v;
  const double u_v = ratio * (params_.null_v + s25_v_per_dps_ * (bias_dps + gain * w_nl_dps));

  if (!started_) {
    // Start in steady state for the first input, with the stationary filter noise.
    filter_state_v_ = u_v + (noise_on_ ? stationary_sigma_v_ * rate_rng_.Normal() : 0.0);
    started_ = true;
  }
  const double mean_v = beta_ * filter_state_v_ + (1.0 - beta_) * u_v + l21_v_ * z1 + l22_v_ * z2;
  filter_state_v_ = a16_ * filter_state_v_ + (1.0 - a16_) * u_v + l11_v_ * z1;

  const double temp_v =
      ratio * (params_.temp_out_v_at_298k +
               temp_out_v_per_k_ * (common::CToK(in.die_temp_c) - kTempOutReference_k)) +
      temp_noise_sigma_v_ * z_temp;
  return Adxrs150Output{static_cast<int32_t>(rate_adc_.SumCounts(mean_v)),
                        static_cast<uint16_t>(temp_adc_.SumCounts(temp_v))};
}

double Adxrs150::RateCountsPerDps() const { return s25_v_per_dps_ * rate_adc_.SumCountsPerVolt(); }

double Adxrs150::NullCounts() const { return params_.null_v * rate_adc_.SumCountsPerVolt(); }

double Adxrs150::OutputFilterCutoff_hz() const {
  return 1.0 / (2.0 * common::kPi * params_.output_filter_r_kohm * kOhmsPerKiloohm *
                params_.output_filter_c_nf * kFaradsPerNanofarad);
}

}  // namespace adahrs::sensor_sim
