// UnitLink's handling of a data frame that passes its CRC but carries a payload no unit sends (a
// splice of an overrun stream whose CRC matches by chance): dropped, counted, and shown as a lost
// packet, never an error that aborts a run. The peer is a pseudo-terminal this test writes to.
#include "hil/drivers/unit_link.h"

#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "firmware_model/unit_firmware.h"
#include "hil/clock.h"

namespace adahrs::hil {
namespace {

namespace fm = firmware_model;

std::vector<uint8_t> RawImuFrame(uint8_t seq) {
  fm::ImuDataPayload data{};
  data.mode = fm::ImuCompensationMode::kRaw;
  for (int ch = 0; ch < 6; ++ch) {
    data.raw.t1_cnt[ch] = 14000;
    data.raw.t2_cnt[ch] = 29000;
  }
  std::array<uint8_t, 300> out{};
  const uint16_t n = fm::EncodeImuDataFrame(data, seq, 0, out.data(), out.size());
  return {out.begin(), out.begin() + n};
}

// An IMU data frame of the compensated length whose mode byte no unit sends, with a valid CRC.
std::vector<uint8_t> MalformedImuFrame(uint8_t seq) {
  std::array<uint8_t, 81> payload{};
  payload.fill(0xEE);
  std::array<uint8_t, 300> out{};
  const uint16_t n = fm::EncodeFrame(static_cast<uint8_t>(fm::PacketType::kImuData),
                                     seq,
                                     0,
                                     payload.data(),
                                     static_cast<uint8_t>(payload.size()),
                                     out.data(),
                                     out.size());
  return {out.begin(), out.begin() + n};
}

TEST(UnitLinkMalformed, CrcValidFrameWithAnImpossiblePayloadIsDroppedAndCountedAsLost) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(::grantpt(master), 0);
  ASSERT_EQ(::unlockpt(master), 0);
  UnitEntry entry;
  entry.role = "imu1";
  entry.kind = UnitKind::kImu;
  entry.port.path = ::ptsname(master);
  entry.port.baud = 115200;
  WallClock clock;
  UnitLink link(entry, clock);
  std::vector<uint8_t> bytes;
  for (const auto& f : {RawImuFrame(1), MalformedImuFrame(2), RawImuFrame(3)})
    bytes.insert(bytes.end(), f.begin(), f.end());
  ASSERT_EQ(::write(master, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  std::vector<ReceivedPacket> got;
  for (int i = 0; i < 20 && got.size() < 2; ++i) {
    const std::vector<ReceivedPacket> more = link.Poll(std::chrono::milliseconds(100));
    got.insert(got.end(), more.begin(), more.end());
  }
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].seq, 1);
  EXPECT_EQ(got[1].seq, 3);
  EXPECT_EQ(link.malformed_data_packets(), 1u);
  EXPECT_EQ(link.lost_packets(), 1u);
  ::close(master);
}

}  // namespace
}  // namespace adahrs::hil
