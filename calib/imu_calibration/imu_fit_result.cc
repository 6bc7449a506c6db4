#include "calib/imu_calibration/imu_fit_result.h"

#include <limits>

namespace adahrs::calib {

firmware_model::ImuCalibrationConstants NotEstimated() {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  firmware_model::ImuCalibrationConstants c;
  for (auto& t : c.thermal) t.k = {kNaN, kNaN, kNaN, kNaN};
  for (auto& a : c.accel) a = {kNaN, kNaN};
  for (auto& g : c.gyro) g = {kNaN, {kNaN, kNaN, kNaN, kNaN}};
  for (auto& row : c.ca_mps2_per_g) row = {kNaN, kNaN, kNaN};
  c.cg = c.ca_mps2_per_g;
  return c;
}

}  // namespace adahrs::calib
