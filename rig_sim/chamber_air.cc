#include "rig_sim/chamber_air.h"

#include <algorithm>
#include <cmath>

namespace adahrs::rig_sim {

ChamberAir::ChamberAir(const ChamberAirParams& params, double initial_c)
    : params_(params), air_c_(initial_c) {}

double ChamberAir::Step(double set_point_c, double dt_s) {
  const double sp_c = std::clamp(set_point_c, params_.min_c, params_.max_c);
  const double error_c = sp_c - air_c_;
  const double heat_c_per_s = params_.heat_rate_c_per_min / 60.0;
  const double cool_c_per_s = params_.cool_rate_c_per_min / 60.0;
  const double linear_c_per_s = error_c / params_.tau_s;
  heat_fraction_ = heat_c_per_s > 0.0 ? std::clamp(linear_c_per_s / heat_c_per_s, 0.0, 1.0) : 0.0;
  cool_fraction_ = cool_c_per_s > 0.0 ? std::clamp(-linear_c_per_s / cool_c_per_s, 0.0, 1.0) : 0.0;
  if (linear_c_per_s > heat_c_per_s || linear_c_per_s < -cool_c_per_s) {
    // Capacity-limited: a straight ramp, never overshooting the set point.
    const double slope = linear_c_per_s > 0 ? heat_c_per_s : -cool_c_per_s;
    const double moved = slope * dt_s;
    air_c_ = std::abs(moved) >= std::abs(error_c) ? sp_c : air_c_ + moved;
  } else {
    air_c_ = sp_c - error_c * std::exp(-dt_s / params_.tau_s);
  }
  // Residual cycling grows in as the error falls inside a few bands of the set point.
  constexpr double kTwoPi = 6.283185307179586;
  phase_rad_ = std::fmod(phase_rad_ + kTwoPi * dt_s / params_.control_period_s, kTwoPi);
  const double settle = std::exp(-std::abs(sp_c - air_c_) / (3.0 * params_.control_band_c + 1e-9));
  cycling_c_ = params_.control_band_c * settle * std::sin(phase_rad_);
  return air_c();
}

}  // namespace adahrs::rig_sim
