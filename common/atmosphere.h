// International Standard Atmosphere (ICAO Doc 7488 / US Standard Atmosphere 1976), geopotential
// altitude, for the troposphere (constant lapse rate, −5 km … 11 km) and the isothermal lower
// stratosphere (11 km … 20 km). Constants and equations: shared/physics.md §4.1 (V via
// [ISA-code]) and shared/protocols.md §5.
//
//   Troposphere:   T = T0 − L·h,  ps = p0·(1 − L·h/T0)^(g0/(R·L))
//   Stratosphere:  T = T11,       ps = p11·exp(−g0·(h − 11 km)/(R·T11))
//
// with p11 and T11 evaluated from the troposphere branch at 11 km, so the two branches join
// continuously. Altitudes are geopotential metres/feet, i.e. pressure altitude as an altimeter
// set to 1013.25 hPa shows it.
//
// Not modelled: layers above 20 km (the 20–32 km branch of protocols.md §5 is outside every
// sensor range here), humidity, the difference between geometric and geopotential height.
// Outside the modelled range every function throws std::domain_error naming the value.
#pragma once

namespace adahrs::common {

/// Sea-level standard pressure p0 (ICAO), Pa.
inline constexpr double kIsaSeaLevelPressure_pa = 101325.0;
/// Sea-level standard temperature T0, K.
inline constexpr double kIsaSeaLevelTemperature_k = 288.15;
/// Troposphere temperature lapse rate L, K/m.
inline constexpr double kIsaLapseRate_k_per_m = 0.0065;
/// Specific gas constant of dry air R used by ISA, J/(kg·K).
inline constexpr double kIsaGasConstant_j_per_kg_k = 287.05287;
/// Ratio of specific heats of air γ.
inline constexpr double kIsaHeatCapacityRatio = 1.4;
/// Tropopause geopotential altitude, m.
inline constexpr double kIsaTropopauseAltitude_m = 11000.0;
/// Lowest and highest altitude modelled here, m.
inline constexpr double kIsaMinAltitude_m = -5000.0;
inline constexpr double kIsaMaxAltitude_m = 20000.0;

/// Static pressure at geopotential altitude `alt_m` in [−5000, 20000] m.
double IsaStaticPressurePa(double alt_m);
/// Pressure altitude (m) of static pressure `ps_pa`, the inverse of IsaStaticPressurePa.
double IsaPressureAltitudeM(double ps_pa);
/// Static temperature at geopotential altitude `alt_m` in [−5000, 20000] m, K.
double IsaTemperatureK(double alt_m);
/// Static pressure at altitude `alt_ft` in feet.
double IsaStaticPressurePaFromFt(double alt_ft);
/// Pressure altitude in feet of static pressure `ps_pa`.
double IsaPressureAltitudeFt(double ps_pa);
/// Speed of sound in air at static temperature `static_temp_k`: a = sqrt(γ·R·T), m/s.
double SpeedOfSoundMps(double static_temp_k);

}  // namespace adahrs::common
