// Emulated constants flash (docs/unit-protocol.md §7): the image layout and CRC recomputed here
// from the document with Boost.CRC, versioning, and detection of every single-bit corruption.
#include "firmware_model/unit_firmware.h"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "hil/codecs/unit_protocol_client.h"

namespace adahrs::firmware_model {
namespace {

// §7: CRC-16/CCITT-FALSE over header and payload words, each word low byte first.
uint16_t DocumentedImageCrc(UnitKind kind, uint16_t version, const std::vector<int16_t>& payload) {
  std::vector<uint16_t> words = {
      0xCA1B, static_cast<uint16_t>(kind), version, static_cast<uint16_t>(payload.size())};
  for (const int16_t word : payload) {
    words.push_back(static_cast<uint16_t>(word));
  }
  std::vector<uint8_t> bytes;
  for (const uint16_t word : words) {
    bytes.push_back(static_cast<uint8_t>(word & 0xFF));
    bytes.push_back(static_cast<uint8_t>(word >> 8));
  }
  return hil::HostCrc16(bytes);
}

TEST(FlashStoreTest, ErasedPageHoldsNoImage) {
  FlashStore flash;
  const FlashImageInfo info = flash.Inspect(UnitKind::kImu);
  EXPECT_EQ(info.status, FlashStatus::kErased);
  EXPECT_EQ(info.constants_version, 0);
  int16_t payload[4] = {7, 7, 7, 7};
  uint16_t count = 99;
  EXPECT_EQ(flash.Load(UnitKind::kImu, payload, 4, &count), FlashStatus::kErased);
  EXPECT_EQ(count, 99);
  EXPECT_EQ(payload[0], 7);
}

TEST(FlashStoreTest, CommitStoresTheDocumentedImageAndCountsVersions) {
  FlashStore flash;
  const std::vector<int16_t> payload = {1, -2, 0x7FFF, -32768, 0};
  ASSERT_EQ(flash.Commit(UnitKind::kAds, payload.data(), 5), FlashStatus::kOk);
  FlashImageInfo info = flash.Inspect(UnitKind::kAds);
  ASSERT_EQ(info.status, FlashStatus::kOk);
  EXPECT_EQ(info.constants_version, 1);
  EXPECT_EQ(info.payload_words, 5);
  EXPECT_EQ(info.image_crc, DocumentedImageCrc(UnitKind::kAds, 1, payload));
  std::vector<int16_t> loaded(8, 0);
  uint16_t count = 0;
  ASSERT_EQ(flash.Load(UnitKind::kAds, loaded.data(), 8, &count), FlashStatus::kOk);
  ASSERT_EQ(count, 5);
  EXPECT_EQ(std::vector<int16_t>(loaded.begin(), loaded.begin() + 5), payload);
  // The other product's firmware does not accept this image.
  EXPECT_EQ(flash.Inspect(UnitKind::kImu).status, FlashStatus::kWrongKind);
  // A second commit replaces the image and increments the version.
  ASSERT_EQ(flash.Commit(UnitKind::kAds, payload.data(), 2), FlashStatus::kOk);
  info = flash.Inspect(UnitKind::kAds);
  EXPECT_EQ(info.constants_version, 2);
  EXPECT_EQ(info.image_crc,
            DocumentedImageCrc(
                UnitKind::kAds, 2, std::vector<int16_t>(payload.begin(), payload.begin() + 2)));
  // A buffer too small for the payload gets nothing.
  EXPECT_EQ(flash.Load(UnitKind::kAds, loaded.data(), 1, &count), FlashStatus::kBadLength);
}

TEST(FlashStoreTest, OversizeCommitIsRefusedAndLeavesTheImage) {
  FlashStore flash;
  std::vector<int16_t> payload(kFlashMaxPayloadWords + 1, 3);
  ASSERT_EQ(flash.Commit(UnitKind::kImu, payload.data(), 4), FlashStatus::kOk);
  EXPECT_EQ(flash.Commit(UnitKind::kImu, payload.data(), kFlashMaxPayloadWords + 1),
            FlashStatus::kBadLength);
  EXPECT_EQ(flash.Inspect(UnitKind::kImu).payload_words, 4);
  EXPECT_EQ(flash.Commit(UnitKind::kImu, payload.data(), kFlashMaxPayloadWords), FlashStatus::kOk);
}

TEST(FlashStoreTest, EverySingleBitFlipInTheImageIsDetected) {
  // CRC-16/CCITT-FALSE detects every single-bit error; header flips are caught earlier by the
  // magic, kind and length checks. Either way the image must stop being valid.
  const std::vector<int16_t> payload = {10, 20, 30, 40, 50, 60};
  const uint16_t image_words = static_cast<uint16_t>(payload.size() + kFlashImageOverheadWords);
  for (uint16_t word = 0; word < image_words; ++word) {
    for (uint8_t bit = 0; bit < 16; ++bit) {
      FlashStore flash;
      ASSERT_EQ(flash.Commit(UnitKind::kImu, payload.data(), 6), FlashStatus::kOk);
      flash.InjectBitFlip(word, bit);
      EXPECT_NE(flash.Inspect(UnitKind::kImu).status, FlashStatus::kOk)
          << "word " << word << " bit " << +bit;
    }
  }
}

}  // namespace
}  // namespace adahrs::firmware_model
