// The executor's interlocks (thesis §3.5, Fig. 45): before an accelerometer acquisition the
// measured gravity vector must match the commanded fixture orientation; before a gyro acquisition
// a table jog must turn the gyro of the orientation's vertical axis, with the right sign.
//
// Both work on raw values of an uncalibrated unit, with nominal design facts only:
//  - ADXL210E: duty 50 % at 0 g and 4 % per g (docs/models/adxl210e.md), so each channel reads
//    g_k = (T1/T2 - 0.5) / 0.04 along its sensitive axis r_k; the nominal channel map and signs
//    (sensor_sim/im3_geometry.h: az1 -z, ax1 -x, ay1 +y, az2 +z, ax2 +x, ay2 -y) give the body
//    specific force f_B = mean over the two channels of each axis of (r_k . e_axis) g_k.
//    A unit at rest with axis a pointing up senses f_B = +1 g e_a (rig_sim/fixture_orientation.h).
//  - ADXRS150: about 20,971.52 counts per deg/s (16 summed 19-bit conversions of 12.5 mV/(deg/s),
//    sensor_sim/adxrs150.h); the table rate w (positive counter-clockwise seen from above)
//    appears as +w about the up-pointing body axis, and gyros gx gy gz look along +x +y +z.
// The zero-g duty of an uncalibrated ADXL210E spreads by up to +-2 g (3 sigma; the rig's drawn
// units show 0.5 g offsets), so an absolute f_B cannot be compared with the expected +1 g:
//  - relative check (the unit passed a check before in this run, in orientation o_ref with f_ref):
//    the change f_B - f_ref must equal up(o) - up(o_ref) within kRelativeTolerance_g = 0.5 g in
//    every component. Offsets cancel; any wrong mount changes some component by >= 1 g.
//  - first check of a unit (no reference): only a gross error is caught — it fails when another
//    orientation explains f_B better than the commanded one by more than kFirstCheckMargin_g = 1 g
//    (a unit mounted upside down: 2 g worse, minus offsets).
// The gyro check uses the change from rest to jog, which no null offset affects.
// Left out: fixture levelling error, misalignment (a few degrees change nothing here).
#pragma once

#include <string>

#include <Eigen/Dense>

#include "calib/executor/unit_logger.h"

namespace adahrs::calib {

struct InterlockVerdict {
  bool ok = false;
  std::string detail;  ///< what was measured and expected, for the journal and the operator
};

/// The up-pointing body axis of a fixture code (11 → +x_B, 32 → -z_B). Throws
/// std::invalid_argument naming the code when it is not one.
Eigen::Vector3d UpAxis_B(int orientation);

/// Body specific force in g from mean raw duties, by the nominal ADXL210E scale and channel map.
Eigen::Vector3d NominalSpecificForce_B_g(const RawAverage& average);

/// A unit's last passed gravity check: what the relative check compares with.
struct GravityReference {
  RawAverage average;
  int orientation = 0;
};

/// The gravity interlock for one unit in `orientation`, relative to `reference` when given.
InterlockVerdict GravityVerdict(const RawAverage& average,
                                int orientation,
                                const GravityReference* reference);

/// The gyro-axis interlock for one unit: `rest` and `jog` averaged at rest and at `jog_rate_dps`.
/// Passes when the gyro of the up axis changed most, in the expected direction, by 50…150 % of
/// the nominal response (the ADXRS150's sensitivity tolerance is far inside that).
InterlockVerdict GyroAxisVerdict(const RawAverage& rest,
                                 const RawAverage& jog,
                                 int orientation,
                                 double jog_rate_dps);

}  // namespace adahrs::calib
