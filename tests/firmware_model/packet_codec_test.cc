// Frame codec (docs/unit-protocol.md §2-3): the worked example from the document, round trips of
// every packet type fed whole and byte by byte, and each rejection path with its counter.
#include "firmware_model/unit_firmware.h"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "hil/codecs/unit_protocol_client.h"

namespace adahrs::firmware_model {
namespace {

constexpr uint8_t kRequest = static_cast<uint8_t>(PacketType::kMaintenanceRequest);
constexpr uint8_t kResponse = static_cast<uint8_t>(PacketType::kMaintenanceResponse);

std::vector<uint8_t> Encode(uint8_t type,
                            uint8_t sequence,
                            uint8_t tag,
                            const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> out(kMaxFrameBytes);
  const uint16_t length = EncodeFrame(type,
                                      sequence,
                                      tag,
                                      payload.data(),
                                      static_cast<uint8_t>(payload.size()),
                                      out.data(),
                                      static_cast<uint16_t>(out.size()));
  out.resize(length);
  return out;
}

// Feeds a stream one byte at a time and collects frames and error events.
struct Collected {
  std::vector<Frame> frames;
  std::vector<DecodeEvent> errors;
};

Collected FeedByBytes(PacketDecoder* decoder, const std::vector<uint8_t>& stream) {
  Collected collected;
  Frame frame;
  for (const uint8_t byte : stream) {
    uint16_t offset = 0;
    while (true) {
      const DecodeResult result =
          decoder->Feed(&byte + offset, static_cast<uint16_t>(1 - offset), &frame);
      offset = static_cast<uint16_t>(offset + result.consumed_bytes);
      if (result.event == DecodeEvent::kNeedMoreBytes) {
        break;
      }
      if (result.event == DecodeEvent::kFrame) {
        collected.frames.push_back(frame);
      } else {
        collected.errors.push_back(result.event);
      }
    }
  }
  return collected;
}

void ExpectFrame(const Frame& frame,
                 uint8_t type,
                 uint8_t sequence,
                 uint8_t tag,
                 const std::vector<uint8_t>& payload) {
  EXPECT_EQ(frame.type, type);
  EXPECT_EQ(frame.sequence, sequence);
  EXPECT_EQ(frame.tag, tag);
  ASSERT_EQ(frame.payload_length, payload.size());
  for (size_t i = 0; i < payload.size(); ++i) {
    EXPECT_EQ(frame.payload[i], payload[i]) << "payload byte " << i;
  }
}

TEST(PacketCodecTest, WorkedExampleOfTheProtocolDocument) {
  // docs/unit-protocol.md §3.1: SET_TAG 42 as request sequence 7; CRC computed by hand from the
  // CRC-16/CCITT-FALSE definition (bitwise, MSB first) is 0x3F83, sent low byte first.
  const std::vector<uint8_t> expected = {
      0xA5, 0x5A, 0x02, 0x20, 0x07, 0x00, 0x02, 0x2A, 0x83, 0x3F};
  EXPECT_EQ(Encode(kRequest, 7, 0, {0x02, 0x2A}), expected);
  hil::UnitProtocolClient client;
  for (int i = 0; i < 7; ++i) {
    client.Identify();
  }
  EXPECT_EQ(client.SetTag(42), expected);
  // The unit's ACK, also from §3.1: response type, tag field already 42, CRC 0x8A9D.
  const std::vector<uint8_t> ack = {
      0xA5, 0x5A, 0x03, 0x21, 0x07, 0x2A, 0x02, 0x00, 0x2A, 0x9D, 0x8A};
  EXPECT_EQ(Encode(kResponse, 7, 42, {0x02, 0x00, 0x2A}), ack);
}

TEST(PacketCodecTest, RoundTripOfEveryPacketTypeWholeAndByteByByte) {
  ImuDataPayload imu{};
  imu.raw.gyro_cnt[1] = 4200000;
  imu.mode = ImuCompensationMode::kSensorCalibrated;
  imu.compensated.value[3] = -123456;
  uint8_t imu_payload[kImuCompensatedPayloadBytes];
  const uint8_t imu_length = EncodeImuPayload(imu, imu_payload, sizeof(imu_payload));
  imu.mode = ImuCompensationMode::kRaw;
  uint8_t imu_raw_payload[kImuCompensatedPayloadBytes];
  const uint8_t imu_raw_length = EncodeImuPayload(imu, imu_raw_payload, sizeof(imu_raw_payload));
  AdsDataPayload ads{};
  ads.raw.ps_cnt = 0x7FFFFF;
  ads.mode = AdsCompensationMode::kSurface;
  uint8_t ads_payload[kAdsCompensatedPayloadBytes];
  const uint8_t ads_length = EncodeAdsPayload(ads, ads_payload, sizeof(ads_payload));
  ads.mode = AdsCompensationMode::kRaw;
  uint8_t ads_raw_payload[kAdsCompensatedPayloadBytes];
  const uint8_t ads_raw_length = EncodeAdsPayload(ads, ads_raw_payload, sizeof(ads_raw_payload));
  std::vector<uint8_t> longest(kMaxPayloadBytes);
  for (size_t i = 0; i < longest.size(); ++i) {
    longest[i] = static_cast<uint8_t>(i * 7);
  }
  struct Case {
    uint8_t type;
    std::vector<uint8_t> payload;
  };
  const std::vector<Case> cases = {
      {0x01, {imu_payload, imu_payload + imu_length}},
      {0x01, {imu_raw_payload, imu_raw_payload + imu_raw_length}},
      {0x02, {ads_payload, ads_payload + ads_length}},
      {0x02, {ads_raw_payload, ads_raw_payload + ads_raw_length}},
      {kRequest, {0x06}},
      {kRequest, longest},
      {kResponse, {0x06, 0x00}},
      {kResponse, longest},
  };
  std::vector<uint8_t> stream;
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::vector<uint8_t> frame = Encode(
        cases[i].type, static_cast<uint8_t>(250 + i), static_cast<uint8_t>(i), cases[i].payload);
    ASSERT_EQ(frame.size(), 8 + cases[i].payload.size());
    // Boost.CRC framing on the PC side produces the same bytes.
    EXPECT_EQ(frame,
              hil::BuildFrame(cases[i].type,
                              static_cast<uint8_t>(250 + i),
                              static_cast<uint8_t>(i),
                              cases[i].payload));
    stream.insert(stream.end(), frame.begin(), frame.end());
  }
  PacketDecoder by_bytes;
  const Collected collected = FeedByBytes(&by_bytes, stream);
  ASSERT_EQ(collected.frames.size(), cases.size());
  EXPECT_TRUE(collected.errors.empty());
  hil::StreamReader whole;
  const std::vector<Frame> frames = whole.Push(stream);
  ASSERT_EQ(frames.size(), cases.size());
  for (size_t i = 0; i < cases.size(); ++i) {
    ExpectFrame(collected.frames[i],
                cases[i].type,
                static_cast<uint8_t>(250 + i),
                static_cast<uint8_t>(i),
                cases[i].payload);
    ExpectFrame(frames[i],
                cases[i].type,
                static_cast<uint8_t>(250 + i),
                static_cast<uint8_t>(i),
                cases[i].payload);
  }
  EXPECT_EQ(whole.counters().frames_ok, cases.size());
  EXPECT_EQ(whole.counters().resync_bytes_skipped, 0u);
}

TEST(PacketCodecTest, EncoderRefusesOversizePayloadAndSmallBuffer) {
  std::vector<uint8_t> payload(251);
  std::vector<uint8_t> out(400, 0xEE);
  EXPECT_EQ(EncodeFrame(kRequest, 0, 0, payload.data(), 251, out.data(), 400), 0);
  EXPECT_EQ(EncodeFrame(kRequest, 0, 0, payload.data(), 10, out.data(), 17), 0);
  EXPECT_EQ(out[0], 0xEE);  // nothing written
  EXPECT_EQ(EncodeFrame(kRequest, 0, 0, payload.data(), 10, out.data(), 18), 18);
  EXPECT_THROW(hil::BuildFrame(kRequest, 0, 0, payload), hil::ProtocolError);
}

TEST(PacketCodecTest, BadCrcIsCountedAndTheNextFrameRecovered) {
  std::vector<uint8_t> stream = Encode(kRequest, 1, 0, {0x06});
  stream[6] ^= 0x10;  // corrupt the command byte
  const std::vector<uint8_t> good = Encode(kRequest, 2, 0, {0x07});
  stream.insert(stream.end(), good.begin(), good.end());
  PacketDecoder decoder;
  const Collected collected = FeedByBytes(&decoder, stream);
  ASSERT_EQ(collected.errors, std::vector<DecodeEvent>{DecodeEvent::kBadCrc});
  ASSERT_EQ(collected.frames.size(), 1u);
  ExpectFrame(collected.frames[0], kRequest, 2, 0, {0x07});
  EXPECT_EQ(decoder.counters().bad_crc, 1u);
  // The damaged frame's 9 bytes were skipped one by one while rescanning.
  EXPECT_EQ(decoder.counters().resync_bytes_skipped, 9u);
}

TEST(PacketCodecTest, LengthNotAllowedForTheTypeIsRefusedAtTheHeader) {
  // An IMU packet must carry 43 or 81 bytes; 44 is refused as soon as the header is in, without
  // waiting for 44 bytes, and a response needs at least command and result (2 bytes).
  std::vector<uint8_t> stream = {0xA5, 0x5A, 44, 0x01};
  const std::vector<uint8_t> short_response = Encode(kResponse, 3, 0, {0x06});
  stream.insert(stream.end(), short_response.begin(), short_response.end());
  const std::vector<uint8_t> good = Encode(kResponse, 4, 0, {0x06, 0x03});
  stream.insert(stream.end(), good.begin(), good.end());
  PacketDecoder decoder;
  const Collected collected = FeedByBytes(&decoder, stream);
  EXPECT_EQ(collected.errors,
            (std::vector<DecodeEvent>{DecodeEvent::kBadLength, DecodeEvent::kBadLength}));
  ASSERT_EQ(collected.frames.size(), 1u);
  ExpectFrame(collected.frames[0], kResponse, 4, 0, {0x06, 0x03});
  EXPECT_EQ(decoder.counters().bad_length, 2u);
}

TEST(PacketCodecTest, UnknownTypeIsCountedAndSkipped) {
  std::vector<uint8_t> stream = Encode(0x7F, 0, 0, {1, 2, 3});
  const std::vector<uint8_t> good = Encode(kRequest, 9, 0, {0x06});
  stream.insert(stream.end(), good.begin(), good.end());
  PacketDecoder decoder;
  const Collected collected = FeedByBytes(&decoder, stream);
  EXPECT_EQ(collected.errors, std::vector<DecodeEvent>{DecodeEvent::kUnknownType});
  ASSERT_EQ(collected.frames.size(), 1u);
  EXPECT_EQ(collected.frames[0].sequence, 9);
  EXPECT_EQ(decoder.counters().unknown_type, 1u);
  EXPECT_EQ(decoder.counters().resync_bytes_skipped, 11u);  // the whole 11-byte unknown frame
}

TEST(PacketCodecTest, GarbageBeforeAFrameIsSkippedAndCounted) {
  std::vector<uint8_t> stream = {0x00, 0xFF, 0x5A, 0xA5, 0xA5, 0x12, 0x34, 0x5A};
  const std::vector<uint8_t> good = Encode(kRequest, 5, 0, {0x06});
  stream.insert(stream.end(), good.begin(), good.end());
  PacketDecoder decoder;
  const Collected collected = FeedByBytes(&decoder, stream);
  EXPECT_TRUE(collected.errors.empty());
  ASSERT_EQ(collected.frames.size(), 1u);
  EXPECT_EQ(decoder.counters().resync_bytes_skipped, 8u);
}

TEST(PacketCodecTest, FalseSyncClaimingALongFrameReleasesTheFramesItSwallowed) {
  // A false sync claiming a 250-byte request holds the decoder until 258 bytes are in; its CRC
  // fails and the rescan from the byte after it finds every real frame inside the window, all
  // completed by the single byte that ended the false candidate.
  std::vector<uint8_t> stream = {0xA5, 0x5A, 250, kRequest};
  std::vector<std::vector<uint8_t>> real;
  while (stream.size() < 300) {
    real.push_back(Encode(kResponse, static_cast<uint8_t>(real.size()), 0, {0x06, 0x00, 0x11}));
    stream.insert(stream.end(), real.back().begin(), real.back().end());
  }
  PacketDecoder decoder;
  const Collected collected = FeedByBytes(&decoder, stream);
  EXPECT_EQ(collected.errors, std::vector<DecodeEvent>{DecodeEvent::kBadCrc});
  ASSERT_EQ(collected.frames.size(), real.size());
  for (size_t i = 0; i < real.size(); ++i) {
    EXPECT_EQ(collected.frames[i].sequence, i);
  }
  EXPECT_EQ(decoder.counters().resync_bytes_skipped, 4u);
}

TEST(PacketCodecTest, ChunkFeedReportsOneEventPerCallAndCountZeroDrainsTheBuffer) {
  std::vector<uint8_t> stream = {0xA5, 0x5A, 250, kRequest};
  for (int i = 0; i < 30; ++i) {
    const std::vector<uint8_t> frame = Encode(kResponse, static_cast<uint8_t>(i), 0, {0x06, 0x00});
    stream.insert(stream.end(), frame.begin(), frame.end());
  }
  PacketDecoder decoder;
  Frame frame;
  // 258 bytes complete the false candidate; the call stops there with the CRC event.
  DecodeResult result = decoder.Feed(stream.data(), 258, &frame);
  EXPECT_EQ(result.event, DecodeEvent::kBadCrc);
  EXPECT_EQ(result.consumed_bytes, 258);
  int frames = 0;
  while ((result = decoder.Feed(nullptr, 0, &frame)).event == DecodeEvent::kFrame) {
    EXPECT_EQ(result.consumed_bytes, 0);
    EXPECT_EQ(frame.sequence, frames);
    ++frames;
  }
  EXPECT_EQ(result.event, DecodeEvent::kNeedMoreBytes);
  EXPECT_EQ(frames, 25);  // (258 - 4) / 10 whole frames were in the window
}

TEST(PacketCodecTest, SequenceTrackerCountsLossAcrossTheWrap) {
  hil::SequenceTracker tracker;
  EXPECT_EQ(tracker.Observe(250), 0u);
  EXPECT_EQ(tracker.Observe(251), 0u);
  EXPECT_EQ(tracker.Observe(254), 2u);  // 252, 253 lost
  EXPECT_EQ(tracker.Observe(1), 2u);    // 255, 0 lost across the wrap
  EXPECT_EQ(tracker.Observe(2), 0u);
  EXPECT_EQ(tracker.lost_total(), 4u);
}

}  // namespace
}  // namespace adahrs::firmware_model
