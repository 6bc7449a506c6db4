// The IMU parts of report.html for one unit, from its calibration data (imu_run_data.h) and, when
// the fit produced one, its constants.json: thermal (per channel the raw output against its fit's
// temperature count with the fitted xi(t), and the residual T = U - xi(t) against chamber
// temperature, up- and down-ramps apart), six-position (Ca per channel, orientation and chamber
// temperature, residual of A along the up axis), gyro (per gyro the Eq. 23 scale-factor curve with
// the fitted cubic, the rate residual per rate, raw and normalised means per acquisition),
// cross-axis (CA, CG with standard errors, residuals at rest and at rate) and noise
// (imu_noise_section.h). Compensated values come from the double reference compensator
// (firmware_model/reference_compensator.h) applied to the recorded raw frames with the file's
// constants.
// Frames and units: body axes B, orientations 11...32; Ca in g, residuals in mg (1 mg =
// 9.80665e-3 m/s^2) and deg/s, CA in m/s^2 per g.
// Section by section: docs/report.md (the section table, "IMU thermal" to "IMU noise").
// Left out: a section whose input is missing says "not available (why)" instead.
#pragma once

#include <string>

#include "calib/constants/constants_file.h"
#include "calib/imu_calibration/imu_run_data.h"

namespace adahrs::calib {

/// Every IMU section of `data`'s unit; `constants` may be null (no fit for this unit).
std::string ImuReportSections(const ImuUnitData& data,
                              const ConstantsFile* constants,
                              double local_gravity_mps2);

}  // namespace adahrs::calib
