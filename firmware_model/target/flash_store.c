#include "flash_store.h"

#include "crc16.h"
#include "q_math.h"

#define ERASED_WORD ((uint16_t)0xFFFFu)
#define MAGIC_INDEX 0u
#define KIND_INDEX 1u
#define VERSION_INDEX 2u
#define COUNT_INDEX 3u
#define PAYLOAD_INDEX 4u

void fw_flash_erase(FwFlashStore* flash) {
  for (uint16_t i = 0u; i < FW_FLASH_PAGE_WORDS; ++i) {
    flash->words[i] = ERASED_WORD;
  }
}

static uint16_t ImageCrc(const FwFlashStore* flash, uint16_t payload_words) {
  uint16_t crc = FW_CRC16_INIT;
  const uint16_t covered_words = (uint16_t)(PAYLOAD_INDEX + payload_words);
  for (uint16_t i = 0u; i < covered_words; ++i) {
    const uint8_t bytes[2] = {(uint8_t)(flash->words[i] & 0xFFu), (uint8_t)(flash->words[i] >> 8)};
    crc = fw_crc16_update(crc, bytes, 2u);
  }
  return crc;
}

FwFlashStatus fw_flash_commit(FwFlashStore* flash,
                              FwUnitKind kind,
                              const int16_t* payload,
                              uint16_t count) {
  if (count > FW_FLASH_MAX_PAYLOAD_WORDS) {
    return FW_FLASH_BAD_LENGTH;
  }
  const FwFlashImageInfo previous = fw_flash_inspect(flash, kind);
  // Version 0 is reserved for "no image"; after 65,535 commits it wraps to 1.
  const uint16_t version = (previous.constants_version == UINT16_MAX)
                               ? (uint16_t)1u
                               : (uint16_t)(previous.constants_version + 1u);
  fw_flash_erase(flash);
  flash->words[MAGIC_INDEX] = FW_FLASH_IMAGE_MAGIC;
  flash->words[KIND_INDEX] = (uint16_t)kind;
  flash->words[VERSION_INDEX] = version;
  flash->words[COUNT_INDEX] = count;
  for (uint16_t i = 0u; i < count; ++i) {
    flash->words[PAYLOAD_INDEX + i] = (uint16_t)payload[i];
  }
  flash->words[PAYLOAD_INDEX + count] = ImageCrc(flash, count);
  return FW_FLASH_OK;
}

FwFlashImageInfo fw_flash_inspect(const FwFlashStore* flash, FwUnitKind kind) {
  FwFlashImageInfo info;
  info.status = FW_FLASH_OK;
  info.constants_version = 0u;
  info.image_crc = 0u;
  info.payload_words = 0u;
  if (flash->words[MAGIC_INDEX] == ERASED_WORD) {
    info.status = FW_FLASH_ERASED;
  } else if (flash->words[MAGIC_INDEX] != FW_FLASH_IMAGE_MAGIC) {
    info.status = FW_FLASH_BAD_MAGIC;
  } else if (flash->words[KIND_INDEX] != (uint16_t)kind) {
    info.status = FW_FLASH_WRONG_KIND;
  } else if (flash->words[COUNT_INDEX] > FW_FLASH_MAX_PAYLOAD_WORDS) {
    info.status = FW_FLASH_BAD_LENGTH;
  } else {
    const uint16_t count = flash->words[COUNT_INDEX];
    const uint16_t stored_crc = flash->words[PAYLOAD_INDEX + count];
    if (stored_crc != ImageCrc(flash, count)) {
      info.status = FW_FLASH_BAD_CRC;
    } else {
      info.constants_version = flash->words[VERSION_INDEX];
      info.image_crc = stored_crc;
      info.payload_words = count;
    }
  }
  return info;
}

FwFlashStatus fw_flash_load(const FwFlashStore* flash,
                            FwUnitKind kind,
                            int16_t* payload,
                            uint16_t capacity,
                            uint16_t* count) {
  const FwFlashImageInfo info = fw_flash_inspect(flash, kind);
  if (info.status != FW_FLASH_OK) {
    return info.status;
  }
  if (info.payload_words > capacity) {
    return FW_FLASH_BAD_LENGTH;
  }
  for (uint16_t i = 0u; i < info.payload_words; ++i) {
    payload[i] = fw_s16_from_bits(flash->words[PAYLOAD_INDEX + i]);
  }
  *count = info.payload_words;
  return FW_FLASH_OK;
}

void fw_flash_inject_bit_flip(FwFlashStore* flash, uint16_t word_index, uint8_t bit) {
  if ((word_index < FW_FLASH_PAGE_WORDS) && (bit <= 15u)) {
    const uint16_t mask = (uint16_t)((uint16_t)1u << bit);
    flash->words[word_index] = (uint16_t)(flash->words[word_index] ^ mask);
  }
}
