// Air temperature in a thermal chamber under its controller (the physics behind the Watlow F4 /
// 942 virtual controllers).
//
// Model: the controlled air approaches the set point as a first-order system whose slope is
// limited by the chamber's heating and cooling capacity,
//   dT/dt = clamp((SP − T)/tau_s, −cool_rate, +heat_rate),
// plus the controller's residual cycling, a slow sinusoid of amplitude control_band_c (±0.3 °C)
// once the air is near the set point. Integrated exactly per step for the linear part.
// Left out: load-dependent capacity, humidity, spatial gradients in the workspace, compressor
// on/off dynamics beyond the residual cycling, a failed heater (faults are injected by the rig).
#pragma once

#include <cstdint>

namespace adahrs::rig_sim {

struct ChamberAirParams {
  double tau_s = 120.0;              ///< closed-loop time constant near the set point
  double heat_rate_c_per_min = 5.0;  ///< heating capacity
  double cool_rate_c_per_min = 3.5;  ///< cooling capacity
  double control_band_c = 0.3;       ///< amplitude of the residual control cycling
  double control_period_s = 90.0;    ///< period of the residual control cycling
  double min_c = -70.0;              ///< lowest reachable air temperature
  double max_c = 180.0;              ///< highest reachable air temperature
};

class ChamberAir {
 public:
  ChamberAir(const ChamberAirParams& params, double initial_c);

  /// Advances `dt_s` with set point `set_point_c`; returns the air temperature.
  double Step(double set_point_c, double dt_s);

  double air_c() const { return air_c_ + cycling_c_; }
  /// The fractions of the heating and the cooling capacity the last Step asked for (the
  /// clamped slope over the capacity).
  double heat_fraction() const { return heat_fraction_; }
  double cool_fraction() const { return cool_fraction_; }

 private:
  ChamberAirParams params_;
  double air_c_;  // the controlled mean
  double cycling_c_ = 0.0;
  double heat_fraction_ = 0.0;
  double cool_fraction_ = 0.0;
  double phase_rad_ = 0.0;
};

}  // namespace adahrs::rig_sim
