// Host exporter: the pipeline's double constants (calibration_constants.h) -> target fixed-point
// blocks (imu_constants.h, ads_constants.h), choosing the normalisation and every exponent, and
// reporting the worst-case quantisation error per output quantity. Each raw-unit polynomial is
// re-expanded exactly in the normalised input the target uses (temperature counts centred in the
// thermal fit's span, gyro counts at the null, ADS codes in the fitted code box), coefficients
// rounded to nearest at their own exponents under the target's overflow rule.
// Units: the constants' raw units in; Q31 mantissas with exponents out; error bounds in output
// units.
// Method, error bound and refusals (std::invalid_argument naming the block and quantity):
// docs/firmware-compensator.md ("Normalisation", the exporter; "Number formats").
#pragma once

#include "firmware_model/calibration_constants.h"
#include "firmware_model/unit_firmware.h"

namespace adahrs::firmware_model {

struct ImuExportReport {
  double accel_g = 0.0;        ///< worst case |error| of a sensor-calibrated accel channel, g
  double rate_dps = 0.0;       ///< of a sensor-calibrated gyro channel, deg/s
  double accel_mps2 = 0.0;     ///< of a fully calibrated A component, m/s^2
  double rate_full_dps = 0.0;  ///< of a fully calibrated G component, deg/s
};

struct AdsExportReport {
  double altitude_ft = 0.0;
  double airspeed_kt = 0.0;
};

struct ImuExport {
  ImuConstants constants;
  ImuExportReport report;
};

struct AdsExport {
  AdsConstants constants;
  AdsExportReport report;
};

/// Exports an IMU set; throws std::invalid_argument with the reason if it cannot be represented.
ImuExport ExportImuConstants(const ImuCalibrationConstants& constants);
/// Exports an ADS set; throws std::invalid_argument with the reason if it cannot be represented.
AdsExport ExportAdsConstants(const AdsCalibrationConstants& constants);

}  // namespace adahrs::firmware_model
