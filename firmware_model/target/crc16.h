// CRC-16/CCITT-FALSE, the frame check of the unit serial protocol (docs/unit-protocol.md §3).
//
// Parameters (Williams/Rocksoft model, as catalogued in the "Catalogue of parametrised CRC
// algorithms", entry CRC-16/IBM-3740 alias CRC-16/CCITT-FALSE): width 16, poly 0x1021,
// init 0xFFFF, refin false, refout false, xorout 0x0000, check ("123456789") 0x29B1.
// Table-driven, one 256-entry uint16 table built at compile time; fixed-width integers only so
// the same source builds for the dsPIC. The host side computes the same CRC with Boost.CRC and a
// test checks that the two agree.
#pragma once

#include <cstdint>

namespace adahrs::firmware_model {

/// Initial register value of CRC-16/CCITT-FALSE.
inline constexpr uint16_t kCrc16Init = 0xFFFF;

/// Continues a CRC-16/CCITT-FALSE over `count` bytes, starting from register value `crc`.
/// Feeding a message in pieces gives the same result as feeding it at once.
uint16_t Crc16Update(uint16_t crc, const uint8_t* bytes, uint16_t count);

/// CRC-16/CCITT-FALSE of `count` bytes (init 0xFFFF, no reflection, no final xor).
uint16_t Crc16CcittFalse(const uint8_t* bytes, uint16_t count);

}  // namespace adahrs::firmware_model
