// ROM tables of the air-data laws the ADS firmware applies after a pressure surface
// (air_data_law.h): ISA pressure altitude against static pressure, and the square of calibrated
// airspeed against impact pressure, at uniform pressure steps that are powers of two, so that the
// index and the interpolation fraction are bit fields of the pressure's Q31 mantissa.
//
// Pressure input: Pa as Q31 at FW_PRESSURE_EXPONENT (mantissa = p * 2^14, |p| < 131,072 Pa).
// ISA altitude: entry k at p = k * 128 Pa, k = 0 ... 1024; ft as Q31 at FW_ALTITUDE_EXPONENT
//   (mantissa = ft * 2^15). Entries below FW_ISA_FIRST_VALID_ENTRY (p < 6,144 Pa, above ~63,500 ft,
//   beyond the 16-bit-ft output and near the ISA's 20 km layer boundary) repeat that entry's value.
// CAS^2: entry k at qc = k * 256 Pa, k = 0 ... 512; kt^2 as Q31 at FW_CAS_SQUARED_EXPONENT
//   (mantissa = kt^2 * 2^12). Entries beyond FW_CAS_LAST_VALID_ENTRY (48,896 Pa, 510 kt; the next
//   would pass 511 kt, beyond the 9-bit-kt output) repeat that entry's value.
// Generated (values and this layout) by firmware_model/air_data_law.h, AirDataTablesSource();
// tests/firmware_model/air_data_law_test.cc checks the compiled tables against it entry by entry
// and rewrites air_data_tables.c with ADAHRS_WRITE_AIR_DATA_TABLES=1. Never edited by hand.
// The tables live in program memory (rom.h); read them with fw_isa_altitude_entry /
// fw_cas_squared_entry (air_data_law.h).
#ifndef ADAHRS_FW_AIR_DATA_TABLES_H
#define ADAHRS_FW_AIR_DATA_TABLES_H

#include <stdint.h>

#include "rom.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FW_PRESSURE_EXPONENT 17     ///< Pa, |p| < 131,072 Pa
#define FW_CAS_SQUARED_EXPONENT 19  ///< kt^2, < 524,288 kt^2

#define FW_ISA_TABLE_STEP_LOG2 21u  ///< 128 Pa = 2^21 mantissa LSB
#define FW_ISA_TABLE_ENTRIES 1025u
#define FW_ISA_FIRST_VALID_ENTRY 48u  ///< 6,144 Pa

#define FW_CAS_TABLE_STEP_LOG2 22u  ///< 256 Pa = 2^22 mantissa LSB
#define FW_CAS_TABLE_ENTRIES 513u
#define FW_CAS_LAST_VALID_ENTRY 191u  ///< qc(511 kt) / 256 Pa = 191.5, rounded down

extern const int32_t fw_isa_altitude_table_q31[FW_ISA_TABLE_ENTRIES] FW_ROM;
extern const int32_t fw_cas_squared_table_q31[FW_CAS_TABLE_ENTRIES] FW_ROM;

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_AIR_DATA_TABLES_H
