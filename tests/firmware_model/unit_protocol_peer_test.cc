// Independent-peer check (STYLE habit 8): a byte stream written by our encoder is decoded by
// tests/firmware_model/unit_protocol_peer.py, a standard-library Python decoder written from
// docs/unit-protocol.md alone (bitwise CRC from the CRC's definition, struct layouts from the
// tables). Every field it reports must equal what the test encoded.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>
#include "adahrs_build_paths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/random.h"
#include "firmware_model/unit_firmware.h"
#include "hil/codecs/unit_protocol_client.h"

namespace adahrs::firmware_model {
namespace {

std::string RunPeer(const std::string& stream_path) {
  const std::string command = std::string(ADAHRS_PYTHON) + " " + ADAHRS_SOURCE_DIR +
                              "/tests/firmware_model/unit_protocol_peer.py " + stream_path;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return {};
  std::string output;
  char buffer[4096];
  size_t n = 0;
  while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) output.append(buffer, n);
  EXPECT_EQ(pclose(pipe), 0) << command;
  return output;
}

TEST(UnitProtocolPeerTest, PythonDecoderReadsOurStreamFieldByField) {
  common::Rng rng(777);
  std::vector<uint8_t> stream;
  std::vector<ImuDataPayload> imu_sent;
  std::vector<AdsDataPayload> ads_sent;
  std::vector<uint8_t> types;
  for (int i = 0; i < 300; ++i) {
    std::vector<uint8_t> frame(kMaxFrameBytes);
    uint16_t length = 0;
    const auto sequence = static_cast<uint8_t>(i);
    const auto tag = static_cast<uint8_t>(i / 50);
    if (i % 3 != 2) {
      ImuDataPayload data{};
      for (int c = 0; c < 6; ++c) {
        data.raw.t1_cnt[c] = static_cast<uint16_t>(rng.NextU64());
        data.raw.t2_cnt[c] = static_cast<uint16_t>(rng.NextU64());
      }
      for (int c = 0; c < 3; ++c) {
        data.raw.gyro_cnt[c] = static_cast<int32_t>(rng.NextU64());
        data.raw.temp_cnt[c] = static_cast<uint16_t>(rng.NextU64());
      }
      data.mode = static_cast<ImuCompensationMode>(rng.NextU64() % 4);
      if (data.mode != ImuCompensationMode::kRaw) {
        for (int32_t& value : data.compensated.value) value = static_cast<int32_t>(rng.NextU64());
        data.compensated.flags = static_cast<uint16_t>(rng.NextU64());
      }
      length = EncodeImuDataFrame(
          data, sequence, tag, frame.data(), static_cast<uint16_t>(frame.size()));
      imu_sent.push_back(data);
    } else {
      AdsDataPayload data{};
      // 24-bit ADS1254 codes, sign-extended.
      data.raw.ps_cnt = static_cast<int32_t>(rng.NextU64() % (1 << 24)) - (1 << 23);
      data.raw.pt_cnt = static_cast<int32_t>(rng.NextU64() % (1 << 24)) - (1 << 23);
      data.raw.ps_bridge_cnt = static_cast<int32_t>(rng.NextU64() % (1 << 23));
      data.raw.pt_bridge_cnt = static_cast<int32_t>(rng.NextU64() % (1 << 23));
      data.raw.oat_cnt = static_cast<int32_t>(rng.NextU64() % (1 << 23));
      data.mode = static_cast<AdsCompensationMode>(rng.NextU64() % 2);
      if (data.mode != AdsCompensationMode::kRaw) {
        for (int32_t& value : data.compensated.value) value = static_cast<int32_t>(rng.NextU64());
        data.compensated.flags = static_cast<uint16_t>(rng.NextU64());
      }
      length = EncodeAdsDataFrame(
          data, sequence, tag, frame.data(), static_cast<uint16_t>(frame.size()));
      ads_sent.push_back(data);
    }
    ASSERT_GT(length, 0);
    types.push_back(frame[3]);
    stream.insert(stream.end(), frame.begin(), frame.begin() + length);
    if (i % 10 == 9) {
      // Garbage between packets, including a sync pair, exercises the peer's resynchronisation.
      for (const uint8_t byte : {0x00, 0xA5, 0x5A, 0x10, 0x01, 0x33}) stream.push_back(byte);
    }
  }
  // A maintenance exchange on the same line.
  hil::UnitProtocolClient client;
  const std::vector<uint8_t> request = client.WriteBlock(0x0E, std::vector<int16_t>{1, -1, 300});
  stream.insert(stream.end(), request.begin(), request.end());

  const std::string path = std::string(ADAHRS_BINARY_DIR) + "/unit_protocol_peer_stream.bin";
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(stream.data()),
             static_cast<std::streamsize>(stream.size()));
  const nlohmann::json decoded = nlohmann::json::parse(RunPeer(path));
  const nlohmann::json& frames = decoded.at("frames");
  ASSERT_EQ(frames.size(), 301u);
  size_t imu_index = 0;
  size_t ads_index = 0;
  for (size_t i = 0; i < 300; ++i) {
    const nlohmann::json& f = frames[i];
    ASSERT_EQ(f.at("type").get<int>(), types[i]);
    EXPECT_EQ(f.at("sequence").get<int>(), static_cast<int>(i % 256));
    EXPECT_EQ(f.at("tag").get<int>(), static_cast<int>(i / 50));
    if (types[i] == 0x01) {
      const ImuDataPayload& sent = imu_sent[imu_index++];
      const nlohmann::json& imu = f.at("imu");
      for (int c = 0; c < 6; ++c) {
        EXPECT_EQ(imu.at("t1_cnt")[c].get<uint16_t>(), sent.raw.t1_cnt[c]);
        EXPECT_EQ(imu.at("t2_cnt")[c].get<uint16_t>(), sent.raw.t2_cnt[c]);
      }
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(imu.at("gyro_cnt")[c].get<int32_t>(), sent.raw.gyro_cnt[c]);
        EXPECT_EQ(imu.at("temp_cnt")[c].get<uint16_t>(), sent.raw.temp_cnt[c]);
      }
      EXPECT_EQ(imu.at("mode").get<int>(), static_cast<int>(sent.mode));
      if (sent.mode != ImuCompensationMode::kRaw) {
        for (int c = 0; c < 9; ++c)
          EXPECT_EQ(imu.at("values")[c].get<int32_t>(), sent.compensated.value[c]);
        EXPECT_EQ(imu.at("flags").get<uint16_t>(), sent.compensated.flags);
      } else {
        EXPECT_FALSE(imu.contains("values"));
      }
    } else {
      const AdsDataPayload& sent = ads_sent[ads_index++];
      const nlohmann::json& ads = f.at("ads");
      const int32_t codes[5] = {sent.raw.ps_cnt,
                                sent.raw.pt_cnt,
                                sent.raw.ps_bridge_cnt,
                                sent.raw.pt_bridge_cnt,
                                sent.raw.oat_cnt};
      for (int c = 0; c < 5; ++c) EXPECT_EQ(ads.at("codes")[c].get<int32_t>(), codes[c]);
      EXPECT_EQ(ads.at("mode").get<int>(), static_cast<int>(sent.mode));
      if (sent.mode != AdsCompensationMode::kRaw) {
        EXPECT_EQ(ads.at("values")[0].get<int32_t>(), sent.compensated.value[0]);
        EXPECT_EQ(ads.at("values")[1].get<int32_t>(), sent.compensated.value[1]);
        EXPECT_EQ(ads.at("flags").get<uint16_t>(), sent.compensated.flags);
      }
    }
  }
  const nlohmann::json& last = frames[300];
  EXPECT_EQ(last.at("type").get<int>(), 0x20);
  EXPECT_EQ(last.at("payload").get<std::vector<int>>(),
            (std::vector<int>{0x03, 0x0E, 3, 0x01, 0x00, 0xFF, 0xFF, 0x2C, 0x01}));
  // Each of the 30 garbage runs holds a false sync whose header (IMU type, length 16) is
  // impossible; the peer and our decoder must both count exactly those.
  EXPECT_EQ(decoded.at("errors").at("bad_length").get<int>(), 30);
  EXPECT_EQ(decoded.at("errors").at("bad_crc").get<int>(), 0);
  hil::StreamReader ours;
  EXPECT_EQ(ours.Push(stream).size(), 301u);
  EXPECT_EQ(ours.counters().bad_length, 30u);
  EXPECT_EQ(ours.counters().bad_crc, 0u);
}

}  // namespace
}  // namespace adahrs::firmware_model
