// The air-data laws of the ADS firmware in double precision (host side, beside target/): ISA
// pressure altitude from static pressure and calibrated airspeed from impact pressure. They are
// the reference the fixed-point laws (target/air_data_law.h) are compared with, and they generate
// the target's ROM tables (target/air_data_tables.h).
//
// ISA (ICAO Doc 7488 / US Standard Atmosphere 1976, geopotential altitude), constants p0 =
// 101,325 Pa, T0 = 288.15 K, L = 0.0065 K/m, R = 287.05287 J/(kg K), g0 = 9.80665 m/s^2:
//   troposphere (p >= p11):  h = T0/L (1 - (p/p0)^(R L/g0))
//   stratosphere (p < p11):  h = 11,000 m + R T11/g0 ln(p11/p),  T11 = 216.65 K,
//                            p11 = p0 (T11/T0)^(g0/(R L)) = 22,632.06 Pa
// Calibrated airspeed, subsonic (CAS < a0): CAS = a0 sqrt(5 ((qc/p0 + 1)^(2/7) - 1)),
// a0 = sqrt(1.4 R T0) = 340.294 m/s; 0 for qc <= 0.
// Units: Pa in, ft and kt out (1 ft = 0.3048 m, 1 kt = 1852/3600 m/s).
// Left out: the layers above 20 km, supersonic CAS (the ADS envelope ends at 50,000 ft, 450 kt).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace adahrs::firmware_model {

double IsaAltitudeFtFromStaticPa(double ps_pa);
double CasKtFromImpactPa(double qc_pa);

/// The ROM tables' entries exactly as target/air_data_tables.h defines them.
std::vector<int32_t> IsaAltitudeTable();
std::vector<int32_t> CasSquaredTable();

/// The text of target/air_data_tables.c for these tables (C99, in program memory: rom.h).
std::string AirDataTablesSource();

}  // namespace adahrs::firmware_model
