#include "sensor_sim/summed_adc.h"

#include <cmath>

namespace adahrs::sensor_sim {
namespace {
// Variance of a rounding error uniform over one LSB, in LSB^2.
constexpr double kUniformRoundingVariance_lsb2 = 1.0 / 12.0;
}  // namespace

SummedAdc::SummedAdc(int bits,
                     double full_scale_v,
                     int conversions,
                     double noise_lsb_rms,
                     bool noise_on,
                     bool quantization_on)
    : codes_per_v_(std::ldexp(1.0, bits) / full_scale_v),
      sum_cnt_per_v_(conversions * codes_per_v_),
      max_code_(std::ldexp(1.0, bits) - 1.0),
      max_sum_cnt_(static_cast<int64_t>(conversions) * ((int64_t{1} << bits) - 1)),
      conversions_(conversions),
      coherent_rounding_(quantization_on && !noise_on),
      quantization_on_(quantization_on),
      mean_noise_variance_v2_(0.0) {
  if (noise_on) {
    const double lsb_v = 1.0 / codes_per_v_;
    const double n = conversions;
    // Per conversion noise, averaged over n conversions.
    double variance_lsb2 = noise_lsb_rms * noise_lsb_rms / n;
    // Dithered quantisation: (n - 1)/12 LSB^2 on the sum, i.e. (n - 1)/12 / n^2 on the mean.
    if (quantization_on) variance_lsb2 += (n - 1.0) * kUniformRoundingVariance_lsb2 / (n * n);
    mean_noise_variance_v2_ = variance_lsb2 * lsb_v * lsb_v;
  }
}

}  // namespace adahrs::sensor_sim
