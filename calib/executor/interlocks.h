// The executor's interlocks (thesis §3.5, Fig. 45): before an accelerometer acquisition the
// measured gravity vector must match the commanded fixture orientation; before a gyro acquisition a
// table jog must turn the gyro of the orientation's vertical axis, with the right sign. Both work
// on raw values of an uncalibrated unit with nominal design facts only (ADXL210E 50 % duty at 0 g
// and 4 % per g; ADXRS150 about 20,971.52 counts per deg/s; the nominal channel map). Zero-g
// offsets of up to +-2 g make the gravity check relative to the unit's last passed check in this
// run (within a tolerance per component); a unit's first check catches gross errors only (a
// margin). The gyro check uses the change from rest to jog. The thresholds are
// InterlockThresholds, the station file's "interlocks" where it sets them (docs/station.md).
// Frames: f_B in g in the body frame; orientation codes as rig_sim/fixture_orientation.h.
// Channel map, signs, tolerances and their reasons: docs/executor.md ("Interlocks").
// Left out: fixture levelling error, misalignment (a few degrees change nothing here).
#pragma once

#include <string>

#include <Eigen/Dense>

#include "calib/executor/unit_logger.h"
#include "hil/station.h"

namespace adahrs::calib {

/// The interlocks' thresholds; the defaults and their reasons: docs/executor.md ("Interlocks").
struct InterlockThresholds {
  /// Relative gravity check: largest error per body component of the change since the last
  /// passed check, g.
  double relative_tolerance_g = 0.5;
  /// First gravity check: how much more gravity another orientation may show than the
  /// commanded one, g.
  double first_check_margin_g = 1.0;
  /// Gyro check: the up axis' response over the nominal one must lie in [min, max].
  double min_gyro_response = 0.5;
  double max_gyro_response = 1.5;
};

/// `base` with what the station's "interlocks" object sets in its place.
InterlockThresholds ThresholdsForStation(const hil::Station& station,
                                         const InterlockThresholds& base = {});
/// The station's interlock attempts, `base` when it sets none.
int InterlockAttemptsForStation(const hil::Station& station, int base);

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
                                const GravityReference* reference,
                                const InterlockThresholds& thresholds = {});

/// The gyro-axis interlock for one unit: `rest` and `jog` averaged at rest and at `jog_rate_dps`.
/// Passes when the gyro of the up axis changed most, in the expected direction, by
/// min_gyro_response…max_gyro_response of the nominal response (by default 50…150 %: the
/// ADXRS150's sensitivity tolerance is far inside that).
InterlockVerdict GyroAxisVerdict(const RawAverage& rest,
                                 const RawAverage& jog,
                                 int orientation,
                                 double jog_rate_dps,
                                 const InterlockThresholds& thresholds = {});

}  // namespace adahrs::calib
