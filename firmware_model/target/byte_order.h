// Little-endian field access for the unit serial protocol (docs/unit-protocol.md §2: every
// multi-byte field is little-endian, the dsPIC's native order). Fixed-width integers only.
// Signed values travel as their two's-complement bit pattern; conversions go through the
// unsigned type so no implementation-defined shift of a negative value happens.
#pragma once

#include <cstdint>

namespace adahrs::firmware_model {

inline void PutU16Le(uint8_t* out, uint16_t value) {
  out[0] = static_cast<uint8_t>(value & 0xFFu);
  out[1] = static_cast<uint8_t>(value >> 8);
}

inline void PutU32Le(uint8_t* out, uint32_t value) {
  out[0] = static_cast<uint8_t>(value & 0xFFu);
  out[1] = static_cast<uint8_t>((value >> 8) & 0xFFu);
  out[2] = static_cast<uint8_t>((value >> 16) & 0xFFu);
  out[3] = static_cast<uint8_t>(value >> 24);
}

inline void PutI16Le(uint8_t* out, int16_t value) { PutU16Le(out, static_cast<uint16_t>(value)); }

inline void PutI32Le(uint8_t* out, int32_t value) { PutU32Le(out, static_cast<uint32_t>(value)); }

inline uint16_t GetU16Le(const uint8_t* in) { return static_cast<uint16_t>(in[0] | (in[1] << 8)); }

inline uint32_t GetU32Le(const uint8_t* in) {
  return static_cast<uint32_t>(in[0]) | (static_cast<uint32_t>(in[1]) << 8) |
         (static_cast<uint32_t>(in[2]) << 16) | (static_cast<uint32_t>(in[3]) << 24);
}

inline int16_t GetI16Le(const uint8_t* in) { return static_cast<int16_t>(GetU16Le(in)); }

inline int32_t GetI32Le(const uint8_t* in) { return static_cast<int32_t>(GetU32Le(in)); }

}  // namespace adahrs::firmware_model
