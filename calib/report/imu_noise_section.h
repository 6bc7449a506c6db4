// The IMU noise part of report.html for one unit: the overlapping Allan deviation (IEEE Std
// 952-1997 Annex C) of the fully calibrated outputs (firmware_model/reference_compensator.h with
// the unit's constants) over its longest acquisition at rest (an accel step, the 0 deg/s rate of
// a gyro step, or a cross-axis acquisition at rest), and the terms read off it
// (calib/solvers/allan_terms.h):
//   gyro            G x y z: Allan deviation in deg/s; angle random walk in deg/sqrt(h) (IEEE 952's
//                   N, read at tau = 1 s), the one-sided density in deg/s/sqrt(Hz) (the datasheets'
//                   convention, sqrt(2) N), bias instability in deg/h with the tau it was read at;
//   accelerometer   A x y z: Allan deviation in mg (1 mg = 9.80665e-3 m/s^2); velocity random walk
//                   in m/s/sqrt(h), the one-sided density in ug/sqrt(Hz), bias instability in ug.
// The figures are log-log, and every tau at which a term was read is in the table. A record that
// never turns up shows no floor: its bias instability is marked as an upper bound.
// The sample interval is the acquisition's mean packet interval. Left out: noise in raw or
// thermal mode (without constants the section says why it is not available), rate random walk
// (a calibration run rests for seconds, not hours).
#pragma once

#include <string>

#include "calib/constants/constants_file.h"
#include "calib/imu_calibration/imu_run_data.h"

namespace adahrs::calib {

/// The noise section's body for `data`'s unit; `constants` may be null (then "not available").
std::string ImuNoiseSection(const ImuUnitData& data, const ConstantsFile* constants);

}  // namespace adahrs::calib
