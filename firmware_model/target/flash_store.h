// Emulated non-volatile store for one committed constants image (docs/unit-protocol.md §7).
//
// Models the unit's constants page (the dsPIC30F's data EEPROM / a program-flash row set) as 512
// 16-bit words that read 0xFFFF when erased. A commit erases the page and programs one image:
//   word 0  magic 0xCA1B          word 1  unit kind (UnitKind)
//   word 2  constants version     word 3  payload word count N
//   words 4 .. 4+N-1  payload     word 4+N  CRC-16/CCITT-FALSE over words 0 .. 3+N, each word
//                                           fed low byte first (the dsPIC's little-endian order)
// The version counts commits (1, 2, ...; 0 means "no valid image"). The image survives a
// simulated power cycle; RAM copies do not. Fixed-width integers, no heap: builds for the dsPIC.
// Not modelled: erase/program timing, endurance, and power loss in the middle of a commit (a
// real unit would need two pages and a sequence number to survive that).
#pragma once

#include <cstdint>

#include "firmware_model/target/unit_protocol.h"

namespace adahrs::firmware_model {

inline constexpr uint16_t kFlashPageWords = 512;
inline constexpr uint16_t kFlashImageMagic = 0xCA1B;
inline constexpr uint16_t kFlashImageOverheadWords = 5;  // 4 header words + CRC
/// Largest payload one image can hold.
inline constexpr uint16_t kFlashMaxPayloadWords = kFlashPageWords - kFlashImageOverheadWords;

enum class FlashStatus : uint8_t {
  kOk,
  kErased,  ///< no image programmed (magic word reads 0xFFFF)
  kBadMagic,
  kWrongKind,  ///< image written by the other product
  kBadLength,  ///< payload count does not fit the page or the caller's buffer
  kBadCrc,
};

/// What Inspect() finds in the page.
struct FlashImageInfo {
  FlashStatus status;
  uint16_t constants_version;  ///< 0 unless status is kOk
  uint16_t image_crc;          ///< stored CRC, 0 unless status is kOk
  uint16_t payload_words;      ///< 0 unless status is kOk
};

class FlashStore {
 public:
  /// An erased page.
  FlashStore();

  /// Erases the page and programs an image of `count` payload words with the next version
  /// (previous valid version + 1, or 1). Returns kBadLength and leaves the page unchanged if
  /// `count` exceeds kFlashMaxPayloadWords.
  FlashStatus Commit(UnitKind kind, const int16_t* payload, uint16_t count);

  /// Validates the page for a unit of `kind` (magic, kind, length, CRC).
  FlashImageInfo Inspect(UnitKind kind) const;

  /// Copies a valid image's payload into `payload` (capacity in words) and sets *count; returns
  /// the Inspect() status, kBadLength if the payload exceeds `capacity`, and copies nothing on
  /// any failure.
  FlashStatus Load(UnitKind kind, int16_t* payload, uint16_t capacity, uint16_t* count) const;

  /// Sets every word to the erased value 0xFFFF.
  void Erase();

  /// Fault injection for tests: flips bit `bit` (0..15) of word `word_index` (ignored if out of
  /// range), as a retention error or a stray write would.
  void InjectBitFlip(uint16_t word_index, uint8_t bit);

 private:
  uint16_t ImageCrc(uint16_t payload_words) const;

  uint16_t words_[kFlashPageWords];
};

}  // namespace adahrs::firmware_model
