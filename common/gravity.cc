#include "common/gravity.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "common/units.h"

namespace adahrs::common {
namespace {

// WGS-84 defining and derived constants, NIMA TR8350.2 tables 3.1, 3.3 and 3.4.
constexpr double kSemiMajorAxis_m = 6378137.0;
constexpr double kFlattening = 1.0 / 298.257223563;
constexpr double kEquatorGravity_mps2 = 9.7803253359;
constexpr double kSomiglianaK = 0.00193185265241;
constexpr double kFirstEccentricitySquared = 0.00669437999013;
// m = ω²·a²·b/GM.
constexpr double kGravityRatioM = 0.00344978650684;

constexpr double kMinHeight_m = -1000.0;
constexpr double kMaxHeight_m = 20000.0;

}  // namespace

double NormalGravityMps2(double geodetic_latitude_deg, double height_m) {
  if (!(geodetic_latitude_deg >= -90.0 && geodetic_latitude_deg <= 90.0)) {
    std::ostringstream message;
    message << "NormalGravityMps2: geodetic_latitude_deg = " << geodetic_latitude_deg
            << " deg is outside [-90, 90] deg";
    throw std::domain_error(message.str());
  }
  if (!(height_m >= kMinHeight_m && height_m <= kMaxHeight_m)) {
    std::ostringstream message;
    message << "NormalGravityMps2: height_m = " << height_m << " m is outside [" << kMinHeight_m
            << ", " << kMaxHeight_m << "] m";
    throw std::domain_error(message.str());
  }
  const double sin_lat = std::sin(common::DegToRad(geodetic_latitude_deg));
  const double sin2_lat = sin_lat * sin_lat;
  const double surface_mps2 = kEquatorGravity_mps2 * (1.0 + kSomiglianaK * sin2_lat) /
                              std::sqrt(1.0 - kFirstEccentricitySquared * sin2_lat);
  const double linear_per_m =
      2.0 / kSemiMajorAxis_m * (1.0 + kFlattening + kGravityRatioM - 2.0 * kFlattening * sin2_lat);
  const double quadratic_per_m2 = 3.0 / (kSemiMajorAxis_m * kSemiMajorAxis_m);
  return surface_mps2 * (1.0 - linear_per_m * height_m + quadratic_per_m2 * height_m * height_m);
}

}  // namespace adahrs::common
