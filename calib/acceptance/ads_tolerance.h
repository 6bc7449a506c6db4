// The ADS accuracy specification (reference-method.md, "Specification the unit must meet",
// thesis Table 2): altitude +-15 ft from -1,000 to 10,000 ft, +-20 ft at 30,000 ft, +-80 ft at
// 50,000 ft; airspeed +-5 kt at 60 kt, +-2 kt at 100, +-1 kt at 300 and 450 kt; over -40...+85 degC
// within the operating limits -1,000...50,000 ft and 30...450 kt.
// Between the table's points the tolerance is interpolated linearly (our reading: the table gives
// points only); below 60 kt the 60 kt tolerance holds, above 300 kt the 1 kt one.
// Not modelled: Mach/TAS tolerances (not specified), correspondence tolerances.
#pragma once

#include <vector>

namespace adahrs::calib {

inline constexpr double kAdsMinAltitudeFt = -1000.0;
inline constexpr double kAdsMaxAltitudeFt = 50000.0;
inline constexpr double kAdsMinAirspeedKt = 30.0;
inline constexpr double kAdsMaxAirspeedKt = 450.0;
inline constexpr double kAdsMinTempC = -40.0;
inline constexpr double kAdsMaxTempC = 85.0;

/// One stated point of the table, with the evaluation's own extra report points (0 and 5,000 ft);
/// the tolerances equal calib::Specification::Reference()
/// (tests/calib/acceptance/specification_test.cc).
struct AdsTolerancePoint {
  double at = 0.0;         ///< ft or kt
  double tolerance = 0.0;  ///< +- ft or kt
};

/// The table's altitude points (-1,000, 0, 5,000, 10,000, 30,000, 50,000 ft) and tolerances.
const std::vector<AdsTolerancePoint>& AltitudeTolerancePoints();
/// The table's airspeed points (60, 100, 300, 450 kt) and tolerances.
const std::vector<AdsTolerancePoint>& AirspeedTolerancePoints();

/// Tolerance (+- ft) at `alt_ft` inside the operating limits; throws std::out_of_range outside.
double AltitudeToleranceFt(double alt_ft);
/// Tolerance (+- kt) at `cas_kt` inside the operating limits; throws std::out_of_range outside.
double AirspeedToleranceKt(double cas_kt);

}  // namespace adahrs::calib
