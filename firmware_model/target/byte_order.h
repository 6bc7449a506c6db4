// Little-endian field access for the unit serial protocol (docs/unit-protocol.md §2: every
// multi-byte field is little-endian, the dsPIC's native order). Fixed-width integers only; every
// byte is widened to the field's own width before it is shifted, so no shift depends on the width
// of int. Signed values travel as their two's-complement bit pattern (q_math.h's conversions).
#ifndef ADAHRS_FW_BYTE_ORDER_H
#define ADAHRS_FW_BYTE_ORDER_H

#include <stdint.h>

#include "q_math.h"

#ifdef __cplusplus
extern "C" {
#endif

static inline void fw_put_u16_le(uint8_t* out, uint16_t value) {
  out[0] = (uint8_t)(value & 0xFFu);
  out[1] = (uint8_t)(value >> 8);
}

static inline void fw_put_u32_le(uint8_t* out, uint32_t value) {
  out[0] = (uint8_t)(value & 0xFFu);
  out[1] = (uint8_t)((value >> 8) & 0xFFu);
  out[2] = (uint8_t)((value >> 16) & 0xFFu);
  out[3] = (uint8_t)(value >> 24);
}

static inline void fw_put_i16_le(uint8_t* out, int16_t value) {
  fw_put_u16_le(out, (uint16_t)value);
}

static inline void fw_put_i32_le(uint8_t* out, int32_t value) {
  fw_put_u32_le(out, (uint32_t)value);
}

static inline uint16_t fw_get_u16_le(const uint8_t* in) {
  return (uint16_t)((uint16_t)in[0] | (uint16_t)((uint16_t)in[1] << 8));
}

static inline uint32_t fw_get_u32_le(const uint8_t* in) {
  return (uint32_t)in[0] | ((uint32_t)in[1] << 8) | ((uint32_t)in[2] << 16) |
         ((uint32_t)in[3] << 24);
}

static inline int16_t fw_get_i16_le(const uint8_t* in) {
  return fw_s16_from_bits(fw_get_u16_le(in));
}

static inline int32_t fw_get_i32_le(const uint8_t* in) {
  return fw_s32_from_bits(fw_get_u32_le(in));
}

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_BYTE_ORDER_H
