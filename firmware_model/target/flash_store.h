// Emulated non-volatile store for one committed constants image (docs/unit-protocol.md §7).
//
// Models the unit's constants page (the dsPIC30F's data EEPROM / a program-flash row set) as 512
// 16-bit words that read 0xFFFF when erased. A commit erases the page and programs one image:
//   word 0  magic 0xCA1B          word 1  unit kind (FwUnitKind)
//   word 2  constants version     word 3  payload word count N
//   words 4 .. 4+N-1  payload     word 4+N  CRC-16/CCITT-FALSE over words 0 .. 3+N, each word
//                                           fed low byte first (the dsPIC's little-endian order)
// The version counts commits (1, 2, ...; 0 means "no valid image"). The image survives a
// simulated power cycle; RAM copies do not. Fixed-width integers, no heap: builds for the dsPIC.
// Not modelled: erase/program timing, endurance, and power loss in the middle of a commit (a
// real unit would need two pages and a sequence number to survive that).
#ifndef ADAHRS_FW_FLASH_STORE_H
#define ADAHRS_FW_FLASH_STORE_H

#include <stdint.h>

#include "unit_protocol.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FW_FLASH_PAGE_WORDS 512u
#define FW_FLASH_IMAGE_MAGIC ((uint16_t)0xCA1Bu)
#define FW_FLASH_IMAGE_OVERHEAD_WORDS 5u  ///< 4 header words + CRC
/// Largest payload one image can hold.
#define FW_FLASH_MAX_PAYLOAD_WORDS (FW_FLASH_PAGE_WORDS - FW_FLASH_IMAGE_OVERHEAD_WORDS)

typedef enum {
  FW_FLASH_OK,
  FW_FLASH_ERASED,  ///< no image programmed (magic word reads 0xFFFF)
  FW_FLASH_BAD_MAGIC,
  FW_FLASH_WRONG_KIND,  ///< image written by the other product
  FW_FLASH_BAD_LENGTH,  ///< payload count does not fit the page or the caller's buffer
  FW_FLASH_BAD_CRC
} FwFlashStatus;

/// What fw_flash_inspect finds in the page.
typedef struct {
  FwFlashStatus status;
  uint16_t constants_version;  ///< 0 unless status is OK
  uint16_t image_crc;          ///< stored CRC, 0 unless status is OK
  uint16_t payload_words;      ///< 0 unless status is OK
} FwFlashImageInfo;

/// The page's words.
typedef struct {
  uint16_t words[FW_FLASH_PAGE_WORDS];
} FwFlashStore;

/// Sets every word to the erased value 0xFFFF (an erased page).
void fw_flash_erase(FwFlashStore* flash);

/// Erases the page and programs an image of `count` payload words with the next version
/// (previous valid version + 1, or 1). Returns BAD_LENGTH and leaves the page unchanged if
/// `count` exceeds FW_FLASH_MAX_PAYLOAD_WORDS.
FwFlashStatus fw_flash_commit(FwFlashStore* flash,
                              FwUnitKind kind,
                              const int16_t* payload,
                              uint16_t count);

/// Validates the page for a unit of `kind` (magic, kind, length, CRC).
FwFlashImageInfo fw_flash_inspect(const FwFlashStore* flash, FwUnitKind kind);

/// Copies a valid image's payload into `payload` (capacity in words) and sets *count; returns
/// the fw_flash_inspect status, BAD_LENGTH if the payload exceeds `capacity`, and copies nothing
/// on any failure.
FwFlashStatus fw_flash_load(const FwFlashStore* flash,
                            FwUnitKind kind,
                            int16_t* payload,
                            uint16_t capacity,
                            uint16_t* count);

/// Fault injection for tests: flips bit `bit` (0..15) of word `word_index` (ignored if out of
/// range), as a retention error or a stray write would.
void fw_flash_inject_bit_flip(FwFlashStore* flash, uint16_t word_index, uint8_t bit);

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // ADAHRS_FW_FLASH_STORE_H
