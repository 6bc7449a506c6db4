// What the units under test and the station's instruments can take: the limits a sequence is
// validated against before anything moves (validation.h). A station file's declared instrument
// limits replace the instrument defaults (station_limits.h); the defaults below are those of the
// reference hardware, each with its source and its status (V verified, R recalled, D derived, E
// estimate, DRV seen in drivers, INF inferred) from shared/physics.md, shared/protocols.md and
// shared/reference-method.md. Units are in the names: °C, °/s, °/s², ft, kt, Pa, per minute, s, Hz.
// Not limited here: the fixture's mechanical limits and centripetal acceleration on the platter
// (under 0.2 g at 150 °/s within 0.25 m of the axis, far inside the ADXL210E's ±10 g), the
// chamber's humidity, the ADTS leak rate.
#pragma once

#include <cstdint>
#include <string>

#include "common/units.h"

namespace adahrs::calib {

struct SequenceLimits {
  // --- The units under test ---
  /// ADXRS150 dynamic range ±150 °/s (physics.md §2, V [RS150P]); the reference Table 1–5
  /// operating limit is the same.
  double unit_gyro_range_dps = 150.0;
  /// Rated temperature range of the units (reference-method.md Table 1–5).
  double unit_temp_min_c = -40.0;
  double unit_temp_max_c = 85.0;
  /// Altitude operating range (reference-method.md Table 1–5).
  double unit_alt_min_ft = -1000.0;
  double unit_alt_max_ft = 50000.0;
  /// Highest calibrated airspeed the unit is specified for (reference-method.md Table 1–5,
  /// 30…450 kt; lower aims down to 0 kt are allowed, they are the pitot zero).
  double unit_cas_max_kt = 450.0;
  /// Highest static pressure a sequence may apply to the ADS static sensor. The model-1230 is a
  /// 0–15 psi part (physics.md §3.1, R), but the unit is specified down to −1,000 ft (15.24 psi)
  /// and the reference calibrated down to −2,000 ft (15.79 psi, thesis Table 25): the limit
  /// allows 1 psi over the rated range. E: the 1230's proof pressure was not retrieved.
  double ads_static_max_pa = common::PsiToPa(16.0);
  /// Highest impact pressure qc on the 0–15 psid pitot sensor (physics.md §3.1, R).
  double ads_pitot_max_pa = common::PsiToPa(15.0);
  /// Safe slew rates of the ADS sensors. E: no datasheet figure was found; these are the rates
  /// the ADTS 405 controls smoothly at (6,000 ft/min) and its standard airspeed rate
  /// (protocols.md §4.7, DOC), which a test set operator would use on a unit.
  double ads_max_alt_rate_ft_per_min = 6000.0;
  double ads_max_cas_rate_kt_per_min = 200.0;

  // --- Rate table (Ideal Aerosmith 1621 class, Aero 8xx controller) ---
  std::string table_name = "rate table";
  /// ATL JOG accepts −360…360 °/s (protocols.md §1.2, DRV).
  double table_max_rate_dps = 360.0;
  /// Rates the table can be commanded to are multiples of this: the ATL JOG command takes an
  /// integer °/s (protocols.md §1.2, DRV; hil/drivers/atl_rate_table refuses anything else).
  double table_rate_resolution_dps = 1.0;
  /// Acceleration the drive can command (E, rig_sim rate-table default; no manual available).
  double table_max_accel_dps2 = 500.0;
  /// The gyro interlock jogs the table at this rate before acquiring (thesis §3.5, Fig. 45b).
  double interlock_jog_rate_dps = 100.0;

  // --- Environmental chamber (Watlow F4 on the IMU bench) ---
  std::string chamber_name = "chamber (Watlow F4)";
  /// Set point limits of the chamber (F4 registers 602/603 as the rig is set up).
  double chamber_min_c = -70.0;
  double chamber_max_c = 180.0;
  /// Fastest ramp the chamber follows (E: typical for benchtop chambers with LN2-free cooling).
  double chamber_max_ramp_c_per_min = 5.0;
  /// Steps a downloaded profile may hold, including its end step (F4: 256 in total,
  /// protocols.md §2.3 register 1219, DRV; a Watlow 942 holds 24, §3.6 DOC).
  int chamber_max_profile_steps = 256;
  /// Jump repeat count range (F4 register 4052 takes 0…9999, INF; 0 would never jump).
  int chamber_max_jump_count = 9999;
  /// Longest ramp-time or soak step: hours 0…99, minutes and seconds 0…59 (registers 4009–4011).
  double chamber_max_step_duration_s = 99.0 * 3600.0 + 59.0 * 60.0 + 59.0;

  // --- Environmental chamber of the ADS bench (Watlow 942) ---
  /// The 942 itself stores profiles of up to 24 steps (protocols.md §3.6, DOC), but its driver
  /// (hil/drivers/watlow942_chamber.h) runs set points only: a thermal_profile step in an ADS
  /// sequence would be refused by the driver after the chamber had soaked. Its set point range
  /// and ramp default to the F4's above (E: the bench's rL/rH are set up per lab, §3.5).
  /// An ADS sequence's chamber steps are checked against these instead of the F4's.
  std::string ads_chamber_name = "chamber (Watlow 942)";
  bool ads_chamber_runs_profiles = false;
  double ads_chamber_min_c = -70.0;
  double ads_chamber_max_c = 180.0;
  double ads_chamber_max_ramp_c_per_min = 5.0;

  // --- Air data test set (Druck ADTS 403/405) ---
  std::string adts_name = "air data test set (ADTS)";
  /// Altitude aims the ADTS controls to (E: not retrieved for the 403/405, §4.5).
  double adts_alt_min_ft = -3000.0;
  double adts_alt_max_ft = 60000.0;
  /// Airspeed aims: the 1,700 mbar Qc range covers 850 kt (protocols.md §4.7, DOC).
  double adts_cas_max_kt = 850.0;
  /// Maximum rates (protocols.md §4.7, DOC).
  double adts_max_alt_rate_ft_per_min = 100000.0;
  double adts_max_cas_rate_kt_per_min = 2000.0;

  // --- Acquisition ---
  /// Packet rate of the units (reference-method.md "The unit": 100 Hz).
  double packet_rate_hz = 100.0;
  /// Most packets one acquisition may ask for (a day at 100 Hz; beyond is a typo).
  int64_t max_packets = 8640000;
  /// Longest log step (a day).
  double max_log_duration_s = 86400.0;
};

}  // namespace adahrs::calib
