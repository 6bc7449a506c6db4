// The IMU parts of report.html for one unit, from its calibration data (imu_run_data.h) and, when
// the fit produced one, its constants.json:
//   thermal     raw channel output vs chamber air temperature over the thermal profile, and the
//               residual after the thermal fit T = U - xi(t) (mean removed), up- and down-ramps
//               drawn separately so hysteresis shows;
//   six-position mean sensor-calibrated Ca per channel (g) in each orientation, and the residual of
//               the fully calibrated A against g_local along the up axis (mg, 1 mg = 9.80665e-3
//               m/s^2);
//   gyro        residual of the sensor-calibrated rate (Eq. 23) against the table's reported rate
//               about the up axis (deg/s) at each rate;
//   cross-axis  CA (m/s^2 per g) and CG with standard errors, and the fully calibrated residuals at
//               rest (mg) and at rate (deg/s) in orientations 11, 21, 31;
//   noise       Allan deviation at rest and the noise terms read off it (imu_noise_section.h).
// Compensated values come from the double reference compensator (firmware_model/
// reference_compensator.h) applied to the recorded raw frames with the file's constants.
// A missing input makes its section say "not available (why)".
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
