// Named unit conversions and physical constants that are definitions, not measurements.
// Formulas use these names instead of bare factors. Local gravity is NOT here: it is a parameter
// of the station (common/gravity.h); kStandardGravity is only the definition of the unit "g".
#pragma once

namespace adahrs::common {

inline constexpr double kPi = 3.14159265358979323846;
/// Standard gravity, the definition of 1 g (CGPM 1901); not the local gravity of any lab.
inline constexpr double kStandardGravity_mps2 = 9.80665;
/// 1 milli-g and 1 micro-g in m/s² (of standard gravity: the unit g of the specifications).
inline constexpr double kMpsPerMilliG = 1e-3 * kStandardGravity_mps2;
inline constexpr double kMpsPerMicroG = 1e-6 * kStandardGravity_mps2;
inline constexpr double kFeetPerMeter = 1.0 / 0.3048;
inline constexpr double kMetersPerFoot = 0.3048;
inline constexpr double kMpsPerKnot = 1852.0 / 3600.0;
inline constexpr double kPaPerPsi = 6894.757293168361;
inline constexpr double kPaPerInHg = 3386.388640341;
inline constexpr double kKelvinAtZeroCelsius = 273.15;

constexpr double FtToM(double ft) { return ft * kMetersPerFoot; }
constexpr double MToFt(double m) { return m * kFeetPerMeter; }
constexpr double KtToMps(double kt) { return kt * kMpsPerKnot; }
constexpr double MpsToKt(double mps) { return mps / kMpsPerKnot; }
constexpr double PsiToPa(double psi) { return psi * kPaPerPsi; }
constexpr double PaToPsi(double pa) { return pa / kPaPerPsi; }
constexpr double InHgToPa(double inhg) { return inhg * kPaPerInHg; }
constexpr double HpaToPa(double hpa) { return hpa * 100.0; }
constexpr double CToK(double c) { return c + kKelvinAtZeroCelsius; }
constexpr double KToC(double k) { return k - kKelvinAtZeroCelsius; }
constexpr double DegToRad(double deg) { return deg * kPi / 180.0; }
constexpr double RadToDeg(double rad) { return rad * 180.0 / kPi; }
constexpr double GToMps2(double g) { return g * kStandardGravity_mps2; }
constexpr double Mps2ToG(double mps2) { return mps2 / kStandardGravity_mps2; }

}  // namespace adahrs::common
