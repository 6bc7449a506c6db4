// The sense of a temperature's last change, the state a thermal hysteresis keeps: +1 after it last
// rose, -1 after it last fell, 0 before its first change. Causal (each value from the path up to
// it, never from a window that looks ahead) and a Schmitt trigger on the path: the sense turns when
// the temperature has moved `band_c` past its extreme since the last turn, so noise on a soak and a
// step between acquisitions are told apart without a rate threshold.
// Not done: a time constant (a slow drift of band_c over hours turns it as a ramp would).
#pragma once

namespace adahrs::diagnosis {

/// Turns within 0.5 degC: above the thermometers' cell-mean noise, below a minute of a 1 degC/min
/// ramp.
inline constexpr double kSenseBand_c = 0.5;

class LastChangeSense {
 public:
  explicit LastChangeSense(double band_c = kSenseBand_c) : band_c_(band_c) {}

  /// The sense after the path reaches `temp_c`.
  double Next(double temp_c) {
    if (!started_) {
      started_ = true;
      low_c_ = high_c_ = temp_c;
      return sense_;
    }
    if (temp_c > high_c_) high_c_ = temp_c;
    if (temp_c < low_c_) low_c_ = temp_c;
    if (sense_ >= 0.0 && temp_c < high_c_ - band_c_) {
      sense_ = -1.0;
      low_c_ = temp_c;
    } else if (sense_ <= 0.0 && temp_c > low_c_ + band_c_) {
      sense_ = 1.0;
      high_c_ = temp_c;
    }
    return sense_;
  }

 private:
  double band_c_;
  bool started_ = false;
  double sense_ = 0.0;
  double low_c_ = 0.0, high_c_ = 0.0;
};

}  // namespace adahrs::diagnosis
