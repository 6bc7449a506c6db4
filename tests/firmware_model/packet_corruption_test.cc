// Randomised corruption of a long packet stream: bit flips, truncation and garbage between packets,
// with a fixed seed. Truth by construction: the test knows which packets went out intact, and the
// decoder must return exactly those, in order: no corrupt packet accepted, every intact packet
// recovered (so it always resynchronises).
#include <cstdint>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "common/random.h"
#include "firmware_model/unit_firmware.h"

namespace adahrs::firmware_model {
namespace {

enum class Fault { kNone, kBitFlips, kTruncation, kGarbageAfter };

std::vector<uint8_t> RandomFrame(common::Rng& rng, uint8_t sequence) {
  std::vector<uint8_t> payload;
  uint8_t type = 0;
  switch (rng.NextU64() % 4) {
    case 0:
      type = static_cast<uint8_t>(PacketType::kImuData);
      payload.resize(rng.NextU64() % 2 == 0 ? kImuRawPayloadBytes : kImuCompensatedPayloadBytes);
      break;
    case 1:
      type = static_cast<uint8_t>(PacketType::kAdsData);
      payload.resize(rng.NextU64() % 2 == 0 ? kAdsRawPayloadBytes : kAdsCompensatedPayloadBytes);
      break;
    case 2:
      type = static_cast<uint8_t>(PacketType::kMaintenanceRequest);
      payload.resize(1 + rng.NextU64() % 90);
      break;
    default:
      type = static_cast<uint8_t>(PacketType::kMaintenanceResponse);
      payload.resize(2 + rng.NextU64() % 90);
      break;
  }
  for (uint8_t& byte : payload) {
    // One byte in eight is a sync byte, so false syncs inside payloads are frequent.
    const uint64_t draw = rng.NextU64();
    byte = draw % 8 == 0 ? (draw % 16 == 0 ? kSyncByte0 : kSyncByte1)
                         : static_cast<uint8_t>(draw >> 8);
  }
  std::vector<uint8_t> frame(kMaxFrameBytes);
  frame.resize(EncodeFrame(type,
                           sequence,
                           static_cast<uint8_t>(rng.NextU64()),
                           payload.data(),
                           static_cast<uint8_t>(payload.size()),
                           frame.data(),
                           static_cast<uint16_t>(frame.size())));
  return frame;
}

// Garbage that often looks like the start of a frame: a sync pair, then a plausible header.
std::vector<uint8_t> RandomGarbage(common::Rng& rng) {
  std::vector<uint8_t> garbage(1 + rng.NextU64() % 40);
  for (uint8_t& byte : garbage) {
    byte = static_cast<uint8_t>(rng.NextU64());
  }
  if (rng.NextU64() % 2 == 0) {
    garbage.insert(garbage.begin() + static_cast<long>(rng.NextU64() % garbage.size()),
                   {kSyncByte0,
                    kSyncByte1,
                    static_cast<uint8_t>(rng.NextU64() % 100),
                    static_cast<uint8_t>(rng.NextU64() % 2 == 0 ? 0x20 : 0x21)});
  }
  return garbage;
}

TEST(PacketCorruptionTest, NoCorruptPacketAcceptedAndEveryIntactPacketRecovered) {
  common::Rng rng(0xC0FFEE);
  constexpr int kPackets = 20000;
  std::vector<uint8_t> stream;
  std::vector<std::vector<uint8_t>> intact;  // frames sent unmodified, in order
  int fault_counts[4] = {};
  for (int i = 0; i < kPackets; ++i) {
    std::vector<uint8_t> frame = RandomFrame(rng, static_cast<uint8_t>(i));
    const uint64_t draw = rng.NextU64() % 100;
    const Fault fault = draw < 55   ? Fault::kNone
                        : draw < 70 ? Fault::kBitFlips
                        : draw < 85 ? Fault::kTruncation
                                    : Fault::kGarbageAfter;
    ++fault_counts[static_cast<int>(fault)];
    if (fault == Fault::kBitFlips) {
      // 1 to 8 flips anywhere in the frame, sync and CRC included; a flip pair that cancels
      // leaves the frame intact, so compare before deciding.
      const std::vector<uint8_t> original = frame;
      const uint64_t flips = 1 + rng.NextU64() % 8;
      for (uint64_t f = 0; f < flips; ++f) {
        frame[rng.NextU64() % frame.size()] ^= static_cast<uint8_t>(1u << (rng.NextU64() % 8));
      }
      if (frame == original) {
        intact.push_back(frame);
      }
    } else if (fault == Fault::kTruncation) {
      frame.resize(1 + rng.NextU64() % (frame.size() - 1));
    } else {
      intact.push_back(frame);
    }
    stream.insert(stream.end(), frame.begin(), frame.end());
    if (fault == Fault::kGarbageAfter) {
      const std::vector<uint8_t> garbage = RandomGarbage(rng);
      stream.insert(stream.end(), garbage.begin(), garbage.end());
    }
  }

  // Feed in random chunk sizes (1..64 bytes) as a UART driver would hand them over.
  PacketDecoder decoder;
  std::vector<std::vector<uint8_t>> decoded;
  size_t offset = 0;
  Frame frame;
  while (offset < stream.size()) {
    const auto chunk =
        static_cast<uint16_t>(std::min<size_t>(1 + rng.NextU64() % 64, stream.size() - offset));
    uint16_t taken = 0;
    while (true) {
      const DecodeResult result = decoder.Feed(
          stream.data() + offset + taken, static_cast<uint16_t>(chunk - taken), &frame);
      taken = static_cast<uint16_t>(taken + result.consumed_bytes);
      if (result.event == DecodeEvent::kFrame) {
        std::vector<uint8_t> bytes(kMaxFrameBytes);
        bytes.resize(EncodeFrame(frame.type,
                                 frame.sequence,
                                 frame.tag,
                                 frame.payload,
                                 frame.payload_length,
                                 bytes.data(),
                                 static_cast<uint16_t>(bytes.size())));
        decoded.push_back(bytes);
      } else if (result.event == DecodeEvent::kNeedMoreBytes) {
        break;
      }
    }
    offset += chunk;
  }

  const DecoderCounters& counters = decoder.counters();
  std::printf("packets %d: intact %zu, bit-flipped %d, truncated %d, garbage-followed %d\n",
              kPackets,
              intact.size(),
              fault_counts[1],
              fault_counts[2],
              fault_counts[3]);
  std::printf("decoded %zu; bad CRC %u, bad length %u, unknown type %u, resync bytes %u\n",
              decoded.size(),
              counters.bad_crc,
              counters.bad_length,
              counters.unknown_type,
              counters.resync_bytes_skipped);
  ASSERT_EQ(decoded.size(), intact.size());
  for (size_t i = 0; i < intact.size(); ++i) {
    ASSERT_EQ(decoded[i], intact[i]) << "decoded frame " << i << " is not the i-th intact frame";
  }
  EXPECT_EQ(counters.frames_ok, intact.size());
  // Every kind of rejection was exercised.
  EXPECT_GT(counters.bad_crc, 1000u);
  EXPECT_GT(counters.bad_length, 100u);
  EXPECT_GT(counters.unknown_type, 100u);
}

}  // namespace
}  // namespace adahrs::firmware_model
