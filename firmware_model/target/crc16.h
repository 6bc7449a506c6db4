// CRC-16/CCITT-FALSE, the frame check of the unit serial protocol (docs/unit-protocol.md §3).
//
// Parameters (Williams/Rocksoft model, as catalogued in the "Catalogue of parametrised CRC
// algorithms", entry CRC-16/IBM-3740 alias CRC-16/CCITT-FALSE): width 16, poly 0x1021,
// init 0xFFFF, refin false, refout false, xorout 0x0000, check ("123456789") 0x29B1.
// Table-driven: one 256-entry uint16 table in ROM (crc16.c; entry i is byte i shifted through 8
// MSB-first division steps, checked against the bitwise definition by crc16_test.cc). The host
// side computes the same CRC with Boost.CRC and a test checks that the two agree.
#ifndef ADAHRS_FW_CRC16_H
#define ADAHRS_FW_CRC16_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Initial register value of CRC-16/CCITT-FALSE.
#define FW_CRC16_INIT ((uint16_t)0xFFFFu)

/// Continues a CRC-16/CCITT-FALSE over `count` bytes, starting from register value `crc`.
/// Feeding a message in pieces gives the same result as feeding it at once.
uint16_t fw_crc16_update(uint16_t crc, const uint8_t* bytes, uint16_t count);

/// CRC-16/CCITT-FALSE of `count` bytes (init 0xFFFF, no reflection, no final xor).
uint16_t fw_crc16_ccitt_false(const uint8_t* bytes, uint16_t count);

/// Entry `index` of the lookup table (tests compare it with the bitwise definition).
uint16_t fw_crc16_table_entry(uint8_t index);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_CRC16_H
