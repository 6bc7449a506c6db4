// Table rate ripple: a once-per-revolution error of the rate table's rate, seen by the gyro whose
// axis is the table axis as a sinusoid at f = |rate| / 360 Hz of amplitude k |rate| (k the table's
// relative rate ripple). It averages away in 1 s cells, so it is measured on the rows: per rate
// segment a least-squares lock-in at f (packet-counter time, phase free per segment) and at
// control frequencies; tested per gyro against chi^2 after the controls' inflation; k estimated
// with its delta-method standard error and checked held out segment by segment.
// Units: k in ppm of the rate (ratio), amplitudes in deg/s, f in Hz.
// Derivation of the test and the estimate: docs/diagnose.md ("Method (IMU)", step 7).
// Left out: harmonics of the revolution frequency, wobble (a tilt of the table axis), a ripple on
// gyros across the table axis.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace adahrs::diagnosis {

/// Segments below this revolution frequency, or shorter than kMinRippleCycles turns, are not
/// used: their lock-in sits in the gyro's flicker floor and the detrend takes part of a turn.
inline constexpr double kMinRippleHz = 0.1;
inline constexpr double kMinRippleCycles = 3.0;

/// The lock-in of one segment at one frequency: raw output units.
struct LockIn {
  double frequency_hz = 0.0;
  double cos_amp = 0.0;
  double sin_amp = 0.0;
  double se = 0.0;  ///< standard error of each of cos_amp and sin_amp (their mean variance)
  double Statistic() const { return (cos_amp * cos_amp + sin_amp * sin_amp) / (se * se); }
};

/// Least-squares lock-in of `y` at `frequency_hz` with an offset and a slope; nullopt when the
/// rows cannot support it (fewer than 8, or a singular design).
std::optional<LockIn> FitLockIn(const std::vector<double>& t_s,
                                const std::vector<double>& y,
                                double frequency_hz);

/// One gyro's lock-ins over one rate segment whose axis is the table axis.
struct RippleSegment {
  int segment = 0;
  double rate_dps = 0.0;  ///< the table's rate, signed
  LockIn at_revolution;
  std::vector<LockIn> controls;
};

/// The ratios of the revolution frequency at which the control lock-ins are taken.
std::vector<double> RippleControlRatios();

/// The lock-ins of one segment's rows, or nullopt when the segment is too slow or too short.
std::optional<RippleSegment> MeasureRipple(int segment,
                                           double rate_dps,
                                           const std::vector<double>& t_s,
                                           const std::vector<double>& y);

struct RippleTest {
  bool testable = false;
  std::string note;  ///< why not, when not testable
  int segments = 0;
  double inflation = 1.0;  ///< control statistic's median over chi^2_2's, at least 1
  double p_value = 1.0;
  double ratio = 0.0;  ///< k
  double ratio_se = 0.0;
  double smallest_detectable_ratio = 0.0;  ///< at `alpha` with the given power
  double held_out_rms_before_dps = 0.0;
  double held_out_rms_after_dps = 0.0;
  std::vector<int> strongest_segments;  ///< largest measured amplitude first, at most 3
};

/// Tests and sizes the ripple from one gyro's segments; `cnt_per_dps` is the channel's scale.
RippleTest TestRipple(const std::vector<RippleSegment>& segments,
                      double cnt_per_dps,
                      double alpha,
                      double power_z);

}  // namespace adahrs::diagnosis
