// CRC-16/CCITT-FALSE of the unit protocol: the target table implementation against the published
// check value and against Boost.CRC (an independent implementation of the same parameters).
#include "firmware_model/unit_firmware.h"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>
#include <boost/crc.hpp>

#include "common/random.h"
#include "hil/codecs/unit_protocol_client.h"

namespace adahrs::firmware_model {
namespace {

using BoostCcittFalse = boost::crc_optimal<16, 0x1021, 0xFFFF, 0, false, false>;

TEST(Crc16Test, PublishedCheckValue) {
  // "Catalogue of parametrised CRC algorithms", CRC-16/IBM-3740 (alias CCITT-FALSE): check 0x29B1.
  const uint8_t message[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(Crc16CcittFalse(message, sizeof(message)), 0x29B1);
  EXPECT_EQ(hil::HostCrc16(message), 0x29B1);
}

// The firmware's ROM table is a literal (C99 has no compile-time evaluation): entry i is the CRC of
// the single byte i from a zero register, which Boost.CRC computes bitwise.
TEST(Crc16Test, RomTableIsTheBitwiseDivisionOfEachByte) {
  for (unsigned i = 0; i < 256; ++i) {
    boost::crc_optimal<16, 0x1021, 0, 0, false, false> bitwise;
    const uint8_t byte = static_cast<uint8_t>(i);
    bitwise.process_byte(byte);
    ASSERT_EQ(fw_crc16_table_entry(byte), bitwise.checksum()) << "entry " << i;
  }
}

TEST(Crc16Test, EmptyMessageIsTheInitialValue) {
  // No xorout, so an empty message leaves the init value 0xFFFF.
  EXPECT_EQ(Crc16CcittFalse(nullptr, 0), 0xFFFF);
}

TEST(Crc16Test, AgreesWithBoostCrcOnRandomMessages) {
  common::Rng rng(20260301);
  for (int trial = 0; trial < 2000; ++trial) {
    const auto length = static_cast<uint16_t>(rng.NextU64() % 300);
    std::vector<uint8_t> message(length);
    for (uint8_t& byte : message) {
      byte = static_cast<uint8_t>(rng.NextU64());
    }
    BoostCcittFalse boost_crc;
    boost_crc.process_bytes(message.data(), message.size());
    ASSERT_EQ(Crc16CcittFalse(message.data(), length), boost_crc.checksum()) << "length " << length;
  }
}

TEST(Crc16Test, IncrementalUpdateEqualsOneShot) {
  const uint8_t message[] = {0xA5, 0x5A, 0x02, 0x20, 0x07, 0x00, 0x02, 0x2A, 0xFF, 0x00};
  const uint16_t one_shot = Crc16CcittFalse(message, sizeof(message));
  for (uint16_t split = 0; split <= sizeof(message); ++split) {
    const uint16_t first = Crc16Update(kCrc16Init, message, split);
    EXPECT_EQ(Crc16Update(first, message + split, static_cast<uint16_t>(sizeof(message) - split)),
              one_shot)
        << "split at " << split;
  }
}

}  // namespace
}  // namespace adahrs::firmware_model
