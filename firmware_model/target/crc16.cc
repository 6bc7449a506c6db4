#include "firmware_model/target/crc16.h"

namespace adahrs::firmware_model {
namespace {

constexpr uint16_t kCrc16Poly = 0x1021;

// Entry i is the register after shifting byte i (placed in the top 8 bits) through 8 steps of the
// MSB-first polynomial division, so one table lookup replaces 8 bitwise steps.
struct Crc16Table {
  uint16_t entry[256];
};

constexpr Crc16Table MakeCrc16Table() {
  Crc16Table table{};
  for (uint16_t i = 0; i < 256; ++i) {
    uint16_t reg = static_cast<uint16_t>(i << 8);
    for (int bit = 0; bit < 8; ++bit) {
      const bool top_bit_set = (reg & 0x8000u) != 0;
      reg = static_cast<uint16_t>(reg << 1);
      if (top_bit_set) {
        reg = static_cast<uint16_t>(reg ^ kCrc16Poly);
      }
    }
    table.entry[i] = reg;
  }
  return table;
}

constexpr Crc16Table kCrc16Table = MakeCrc16Table();

}  // namespace

uint16_t Crc16Update(uint16_t crc, const uint8_t* bytes, uint16_t count) {
  for (uint16_t i = 0; i < count; ++i) {
    const uint8_t index = static_cast<uint8_t>((crc >> 8) ^ bytes[i]);
    crc = static_cast<uint16_t>((crc << 8) ^ kCrc16Table.entry[index]);
  }
  return crc;
}

uint16_t Crc16CcittFalse(const uint8_t* bytes, uint16_t count) {
  return Crc16Update(kCrc16Init, bytes, count);
}

}  // namespace adahrs::firmware_model
