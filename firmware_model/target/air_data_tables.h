// ROM tables of the air-data laws the ADS firmware applies after a pressure surface
// (air_data_law.h): ISA pressure altitude against static pressure, and the square of calibrated
// airspeed against impact pressure, at uniform pressure steps that are powers of two, so that the
// index and the interpolation fraction are bit fields of the pressure's Q31 mantissa.
//
// Pressure input: Pa as Q31 at kPressureExponent (mantissa = p * 2^14, |p| < 131,072 Pa).
// ISA altitude: entry k at p = k * 128 Pa, k = 0 ... 1024; ft as Q31 at kAltitudeExponent
//   (mantissa = ft * 2^15). Entries below kIsaFirstValidEntry (p < 6,144 Pa, above ~63,500 ft,
//   beyond the 16-bit-ft output and near the ISA's 20 km layer boundary) repeat that entry's value.
// CAS^2: entry k at qc = k * 256 Pa, k = 0 ... 512; kt^2 as Q31 at kCasSquaredExponent
//   (mantissa = kt^2 * 2^12). Entries beyond kCasLastValidEntry (48,896 Pa, 510 kt; the next
//   would pass 511 kt, beyond the 9-bit-kt output) repeat that entry's value.
// Generated (values and this layout) by firmware_model/air_data_law.h, AirDataTablesSource();
// tests/firmware_model/air_data_law_test.cc checks the compiled tables against it entry by entry
// and rewrites air_data_tables.cc with ADAHRS_WRITE_AIR_DATA_TABLES=1. Never edited by hand.
#pragma once

#include <cstdint>

namespace adahrs::firmware_model {

inline constexpr int8_t kPressureExponent = 17;    ///< Pa, |p| < 131,072 Pa
inline constexpr int8_t kCasSquaredExponent = 19;  ///< kt^2, < 524,288 kt^2

inline constexpr uint8_t kIsaTableStepLog2 = 21;  ///< 128 Pa = 2^21 mantissa LSB
inline constexpr uint16_t kIsaTableEntries = 1025;
inline constexpr uint16_t kIsaFirstValidEntry = 48;  ///< 6,144 Pa

inline constexpr uint8_t kCasTableStepLog2 = 22;  ///< 256 Pa = 2^22 mantissa LSB
inline constexpr uint16_t kCasTableEntries = 513;
inline constexpr uint16_t kCasLastValidEntry = 191;  ///< qc(511 kt) / 256 Pa = 191.5, rounded down

extern const int32_t kIsaAltitudeTableQ31[kIsaTableEntries];
extern const int32_t kCasSquaredTableQ31[kCasTableEntries];

}  // namespace adahrs::firmware_model
