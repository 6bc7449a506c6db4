// Where the firmware's constant tables live and how they are read: the CRC table (crc16.c) and the
// air-data law tables (air_data_tables.c), 6.7 KB in all, which belong in program memory.
// dsPIC30F/33F with MPLAB XC16: const data is placed in program memory and read through the PSV
// window with ordinary loads (the compiler's default constants-in-code model), so FW_ROM is empty
// and a read is a plain dereference, as on the host.
// AVR (the 16-bit-int proof build, tests/firmware_model/avr/): program memory is a separate
// address space, so the tables carry avr-libc's PROGMEM and are read with pgm_read_word /
// pgm_read_dword (the image stays below 64 KB, the reach of these near reads).
#ifndef ADAHRS_FW_ROM_H
#define ADAHRS_FW_ROM_H

#include <stdint.h>

#include "q_math.h"

#if defined(__AVR__)
#include <avr/pgmspace.h>
#define FW_ROM PROGMEM
#else
#define FW_ROM
#endif

#ifdef __cplusplus
extern "C" {
#endif

/// Reads a uint16 of a table declared FW_ROM.
static inline uint16_t fw_rom_read_u16(const uint16_t* entry) {
#if defined(__AVR__)
  return pgm_read_word(entry);
#else
  return *entry;
#endif
}

/// Reads an int32 of a table declared FW_ROM.
static inline int32_t fw_rom_read_i32(const int32_t* entry) {
#if defined(__AVR__)
  return fw_s32_from_bits(pgm_read_dword(entry));
#else
  return *entry;
#endif
}

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_ROM_H
