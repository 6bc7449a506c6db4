// A unipolar ADC channel whose output per frame is the SUM of several conversions, as the unit
// reads its gyros (external 19-bit ADC, 0..5 V, 16 conversions per 100 Hz frame, int32 sum) and
// their TEMP pins (dsPIC 12-bit ADC, 0..5 V, 16 conversions, uint16 sum up to 65520), given the
// mean input voltage over the frame: without dither every conversion gives the same code (the
// staircase), with dither the rounding errors are independent (Widrow) and added as variance
// before one final rounding; with quantisation off the ideal sum at 1-count resolution. The caller
// adds all analog noise and MeanNoiseVariance_v2() to the mean voltage before SumCounts.
// Units: input in V, noise in LSB rms per conversion, output in counts (_cnt).
// Derivation: docs/models/adxrs150.md ("Equations", the ADC item); scales: reference-method.md
// "Scales implied".
// Left out: differential/integral nonlinearity, reference error and drift, partially clipped
// frames (the clip applies to the frame mean).
#pragma once

#include <algorithm>
#include <cstdint>

#include "sensor_sim/fast_math.h"

namespace adahrs::sensor_sim {

class SummedAdc {
 public:
  /// `bits` of resolution over [0, full_scale_v], `conversions` summed per frame, ADC noise
  /// `noise_lsb_rms` per conversion (used only if `noise_on`).
  SummedAdc(int bits,
            double full_scale_v,
            int conversions,
            double noise_lsb_rms,
            bool noise_on,
            bool quantization_on);

  /// Variance, in V^2, that the converter adds to the mean input of one frame (ADC noise and, when
  /// dithered, the quantisation noise beyond the final rounding). Zero when noise is off.
  double MeanNoiseVariance_v2() const { return mean_noise_variance_v2_; }

  /// The frame's summed counts for mean input voltage `mean_v` (noise already added). Inline: it
  /// runs for every gyro channel every frame. The clipped code is at most 2^bits·conversions, far
  /// inside RoundHalfAwayToInt64's exact range, where it equals std::llround.
  int64_t SumCounts(double mean_v) const {
    const double code = std::clamp(mean_v * codes_per_v_, 0.0, max_code_);
    if (coherent_rounding_) return conversions_ * RoundHalfAwayToInt64(code);
    return RoundHalfAwayToInt64(code * conversions_);
  }

  /// Counts of the sum per volt of mean input: conversions · 2^bits / full_scale_v.
  double SumCountsPerVolt() const { return sum_cnt_per_v_; }
  /// Largest possible sum: conversions · (2^bits - 1).
  int64_t MaxSumCounts() const { return max_sum_cnt_; }

 private:
  double codes_per_v_;
  double sum_cnt_per_v_;
  double max_code_;
  int64_t max_sum_cnt_;
  int conversions_;
  bool coherent_rounding_;
  bool quantization_on_;
  double mean_noise_variance_v2_;
};

}  // namespace adahrs::sensor_sim
