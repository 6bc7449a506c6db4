#include "firmware_model/target/flash_store.h"

#include "firmware_model/target/crc16.h"

namespace adahrs::firmware_model {
namespace {

constexpr uint16_t kErasedWord = 0xFFFF;
constexpr uint16_t kMagicIndex = 0;
constexpr uint16_t kKindIndex = 1;
constexpr uint16_t kVersionIndex = 2;
constexpr uint16_t kCountIndex = 3;
constexpr uint16_t kPayloadIndex = 4;

}  // namespace

FlashStore::FlashStore() { Erase(); }

void FlashStore::Erase() {
  for (uint16_t i = 0; i < kFlashPageWords; ++i) {
    words_[i] = kErasedWord;
  }
}

uint16_t FlashStore::ImageCrc(uint16_t payload_words) const {
  uint16_t crc = kCrc16Init;
  const uint16_t covered_words = static_cast<uint16_t>(kPayloadIndex + payload_words);
  for (uint16_t i = 0; i < covered_words; ++i) {
    const uint8_t bytes[2] = {static_cast<uint8_t>(words_[i] & 0xFFu),
                              static_cast<uint8_t>(words_[i] >> 8)};
    crc = Crc16Update(crc, bytes, 2);
  }
  return crc;
}

FlashStatus FlashStore::Commit(UnitKind kind, const int16_t* payload, uint16_t count) {
  if (count > kFlashMaxPayloadWords) {
    return FlashStatus::kBadLength;
  }
  const FlashImageInfo previous = Inspect(kind);
  const uint16_t version = static_cast<uint16_t>(previous.constants_version + 1);
  Erase();
  words_[kMagicIndex] = kFlashImageMagic;
  words_[kKindIndex] = static_cast<uint16_t>(kind);
  // Version 0 is reserved for "no image"; after 65,535 commits it wraps to 1.
  words_[kVersionIndex] = version == 0 ? 1 : version;
  words_[kCountIndex] = count;
  for (uint16_t i = 0; i < count; ++i) {
    words_[kPayloadIndex + i] = static_cast<uint16_t>(payload[i]);
  }
  words_[kPayloadIndex + count] = ImageCrc(count);
  return FlashStatus::kOk;
}

FlashImageInfo FlashStore::Inspect(UnitKind kind) const {
  FlashImageInfo info = {FlashStatus::kOk, 0, 0, 0};
  if (words_[kMagicIndex] == kErasedWord) {
    info.status = FlashStatus::kErased;
  } else if (words_[kMagicIndex] != kFlashImageMagic) {
    info.status = FlashStatus::kBadMagic;
  } else if (words_[kKindIndex] != static_cast<uint16_t>(kind)) {
    info.status = FlashStatus::kWrongKind;
  } else if (words_[kCountIndex] > kFlashMaxPayloadWords) {
    info.status = FlashStatus::kBadLength;
  } else {
    const uint16_t count = words_[kCountIndex];
    const uint16_t stored_crc = words_[kPayloadIndex + count];
    if (stored_crc != ImageCrc(count)) {
      info.status = FlashStatus::kBadCrc;
    } else {
      info.constants_version = words_[kVersionIndex];
      info.image_crc = stored_crc;
      info.payload_words = count;
    }
  }
  return info;
}

FlashStatus FlashStore::Load(UnitKind kind,
                             int16_t* payload,
                             uint16_t capacity,
                             uint16_t* count) const {
  const FlashImageInfo info = Inspect(kind);
  if (info.status != FlashStatus::kOk) {
    return info.status;
  }
  if (info.payload_words > capacity) {
    return FlashStatus::kBadLength;
  }
  for (uint16_t i = 0; i < info.payload_words; ++i) {
    payload[i] = static_cast<int16_t>(words_[kPayloadIndex + i]);
  }
  *count = info.payload_words;
  return FlashStatus::kOk;
}

void FlashStore::InjectBitFlip(uint16_t word_index, uint8_t bit) {
  if (word_index >= kFlashPageWords || bit > 15) {
    return;
  }
  words_[word_index] = static_cast<uint16_t>(words_[word_index] ^ (1u << bit));
}

}  // namespace adahrs::firmware_model
