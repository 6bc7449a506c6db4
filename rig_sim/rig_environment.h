// The physical state of the virtual lab at one instant of simulated time: what the instruments
// create and the mounted units experience. Instruments write their part each world frame; unit
// devices read it. Nothing here knows about serial ports or protocols.
//
// Frames: L lab local-level (z up), P rate-table platter (its axis is L's z), B unit case.
// A unit mounted on the table in orientation code c (rig_sim/fixture_orientation.h) has its up
// axis along the table axis, so w_B = table_rate_dps · UpAxis_B(c) and, at rest on a level table,
// f_B = (local_gravity / g0) · UpAxis_B(c) in g.
// Left out: table wobble and fixture levelling error (added by the table model when configured),
// centripetal acceleration at the unit's radius (units are mounted on the axis), Earth rate.
#pragma once

#include <array>

namespace adahrs::rig_sim {

inline constexpr int kMaxImuUnits = 4;
inline constexpr int kMaxAdsUnits = 4;

struct RigEnvironment {
  double time_s = 0.0;                  ///< simulated time since the rig started
  double imu_chamber_air_c = 25.0;      ///< air around the IMU units (F4 chamber on the table)
  double ads_chamber_air_c = 25.0;      ///< air around the ADS units (942 bench chamber)
  double table_angle_deg = 0.0;         ///< platter angle about the table axis
  double table_rate_dps = 0.0;          ///< platter rate about the (up) table axis
  double ps_pa = 101325.0;              ///< static pressure delivered to the ADS static ports
  double qc_pa = 0.0;                   ///< impact pressure (pitot − static) delivered
  double local_gravity_mps2 = 9.80665;  ///< station gravity (a station parameter)
  double supply_v = 5.0;                ///< units' supply rail
  std::array<int, kMaxImuUnits> imu_orientation{31, 31, 31, 31};  ///< fixture code per IMU slot
};

}  // namespace adahrs::rig_sim
