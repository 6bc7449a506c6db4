// Host exporter: the pipeline's double constants (calibration_constants.h) -> target fixed-point
// blocks (imu_constants.h, ads_constants.h), choosing the normalisation and every exponent, and
// reporting the worst-case quantisation error per output quantity.
//
// Method. Each raw-unit polynomial p(v) = sum k_j (v - v0)^j is re-expanded exactly (long double
// binomial sums) in the normalised input x = (v - centre) 2^-shift with the integer centre the
// target uses; c_m = sum_{j>=m} k_j C(j,m) (centre - v0)^(j-m) 2^(shift m). The working exponent is
// the smallest E with sum |c_m| < 2^E (the target's overflow rule), each coefficient gets the
// smallest exponent e >= E - 16 with |c| < 2^e and a mantissa rounded to nearest. Normalisation:
// temperature counts centred in the span the thermal fit covers, the smallest power-of-two
// half-range holding 1.25x its half-width (at most 2^16); gyro counts centred at
// the null (rounded to 1/256 count), shift 22 (+-4.19e6 counts, ~+-200 deg/s); ADS codes centred
// in the fitted code box, smallest shift covering it.
// Error bound per quantity (reported, in output units): sum of |c - c_quantised| at |x| = 1,
// plus 4 LSB of the working exponent per Horner step (MulQ31 is within 3 LSB, the alignment floor
// 1 LSB), carried through the later stages by the magnitude of their gain.
// Refusal: std::invalid_argument naming the block and the quantity that does not fit (e.g. a
// thermal drift beyond the channel's U full scale, a gyro cubic beyond +-256 deg/s over the
// normalised span, a matrix row that overflows at the rated input).
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
