// Reference accelerometer offset and scale (thesis section 2.8.2, Eq. 12-22): six orientations
// 11 12 21 22 31 32 (docs/frames-and-units.md: axis x/y/z up, then down), per channel
//   T(axis up) = O + S g_l,   T(axis down) = O - S g_l,
// on thermally compensated means T (duty), where g_l = g_local / 9.80665 is the station's gravity
// in g, so that Ca = (T - O) / S reads g along the channel's body axis (both channels of an axis
// read +g_l with it up; S < 0 for the channels that sense the negative axis, as Table 16's signs).
// This is Eq. 17-20, O = (U+ + U-)/2, S = (U+ - U-)/(2 g_l): the reference divides by 1 (local g);
// we divide by g_l so that the constants are in the unit g = 9.80665 m/s^2 of compensated_frame.h.
// Solved per channel by the driver with known variances (two observations, two unknowns), so
//   se(O) = sqrt(se+^2 + se-^2) / 2,   se(S) = sqrt(se+^2 + se-^2) / (2 g_l).
// Refused: a missing or repeated orientation (naming the channels it is needed for), a mean that is
// not finite or a standard error that is not positive.
// Not modelled: fixture tilt (each face is taken as exactly level), sensitivity to the other axes
// (cross-axis calibration removes it afterwards), nonlinearity (two points define a line).
#pragma once

#include <array>
#include <vector>

#include "firmware_model/calibration_constants.h"

namespace adahrs::calib {

/// Thermally compensated per-channel means of one orientation step (az1 ax1 ay1 az2 ax2 ay2).
struct AccelOrientationMeans {
  int orientation = 0;                ///< 11, 12, 21, 22, 31 or 32
  std::array<double, 6> t_duty{};     ///< mean T, duty
  std::array<double, 6> t_duty_se{};  ///< standard error of each mean, duty
};

struct AccelScaleEstimate {
  firmware_model::AccelScaleFit fit;  ///< offset_duty, scale_duty_per_g
  double offset_se_duty = 0.0;
  double scale_se_duty_per_g = 0.0;
  double inverse_scale_g_per_duty = 0.0;     ///< 1/S, the reference's ~ +-25 (Table 16)
  double inverse_scale_se_g_per_duty = 0.0;  ///< se(S) / S^2
};

/// Fits all six channels; throws DegenerateDesignError (linear_least_squares.h) with the reason.
std::array<AccelScaleEstimate, 6> FitSixPosition(const std::vector<AccelOrientationMeans>& steps,
                                                 double g_local_mps2);

}  // namespace adahrs::calib
