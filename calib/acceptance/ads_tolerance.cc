#include "calib/acceptance/ads_tolerance.h"

#include <stdexcept>

#include <fmt/format.h>

namespace adahrs::calib {
namespace {

// Linear interpolation through (at, tolerance) knots sorted by `at`, constant beyond the ends.
double Interpolate(const std::vector<AdsTolerancePoint>& knots, double at) {
  if (at <= knots.front().at) return knots.front().tolerance;
  for (size_t i = 1; i < knots.size(); ++i) {
    if (at <= knots[i].at) {
      const AdsTolerancePoint& a = knots[i - 1];
      const AdsTolerancePoint& b = knots[i];
      return a.tolerance + (b.tolerance - a.tolerance) * (at - a.at) / (b.at - a.at);
    }
  }
  return knots.back().tolerance;
}

}  // namespace

const std::vector<AdsTolerancePoint>& AltitudeTolerancePoints() {
  static const std::vector<AdsTolerancePoint> points = {{-1000.0, 15.0},
                                                        {0.0, 15.0},
                                                        {5000.0, 15.0},
                                                        {10000.0, 15.0},
                                                        {30000.0, 20.0},
                                                        {50000.0, 80.0}};
  return points;
}

const std::vector<AdsTolerancePoint>& AirspeedTolerancePoints() {
  static const std::vector<AdsTolerancePoint> points = {
      {60.0, 5.0}, {100.0, 2.0}, {300.0, 1.0}, {450.0, 1.0}};
  return points;
}

double AltitudeToleranceFt(double alt_ft) {
  if (!(alt_ft >= kAdsMinAltitudeFt && alt_ft <= kAdsMaxAltitudeFt)) {
    throw std::out_of_range(fmt::format("altitude {} ft outside the operating limits {}..{} ft",
                                        alt_ft,
                                        kAdsMinAltitudeFt,
                                        kAdsMaxAltitudeFt));
  }
  return Interpolate(AltitudeTolerancePoints(), alt_ft);
}

double AirspeedToleranceKt(double cas_kt) {
  if (!(cas_kt >= kAdsMinAirspeedKt && cas_kt <= kAdsMaxAirspeedKt)) {
    throw std::out_of_range(fmt::format("airspeed {} kt outside the operating limits {}..{} kt",
                                        cas_kt,
                                        kAdsMinAirspeedKt,
                                        kAdsMaxAirspeedKt));
  }
  return Interpolate(AirspeedTolerancePoints(), cas_kt);
}

}  // namespace adahrs::calib
