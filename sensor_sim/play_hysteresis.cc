#include "sensor_sim/play_hysteresis.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace adahrs::sensor_sim {

PlayHysteresis::PlayHysteresis(double span, double low, double high) {
  if (!(span > 0.0) || !(high > low)) {
    throw std::invalid_argument("PlayHysteresis: span " + std::to_string(span) +
                                " must be > 0 and the range [" + std::to_string(low) + ", " +
                                std::to_string(high) + "] not empty");
  }
  double total = 0.0;
  for (int i = 0; i < kOperators; ++i) {
    radius_[i] = 0.5 * span * (i + 1) / kOperators;
    weight_[i] = std::exp(-radius_[i] / (0.15 * span));
    total += weight_[i];
  }
  for (double& w : weight_) w /= total;
  centre_ = 0.5 * (low + high);
  inv_half_range_ = 2.0 / (high - low);
}

double PlayHysteresis::Update(double x) {
  if (!started_) {
    started_ = true;
    play_.fill(x);
    return state_;
  }
  double sum = 0.0;
  for (int i = 0; i < kOperators; ++i) {
    play_[i] = std::clamp(play_[i], x - radius_[i], x + radius_[i]);
    sum += weight_[i] * (play_[i] - x) / radius_[i];
  }
  const double envelope = 1.0 + kEnvelopeSlope * (x - centre_) * inv_half_range_;
  state_ = std::clamp(envelope * sum, -1.0, 1.0);
  return state_;
}

}  // namespace adahrs::sensor_sim
