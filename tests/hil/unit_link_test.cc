// UnitLink against the virtual rig as a separate process (tests/support/rig_process.h): every
// request of the unit protocol, the TAG in the packets, zero loss over simulated minutes, and the
// faults the executor must report (a silent unit, a NAK, a unit of the wrong kind).
// ctest: RUN_SERIAL — the silent-unit test times its drain on the wall clock.
#include "hil/drivers/unit_link.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "firmware_model/constants_exporter.h"
#include "hil/drivers/unit_serial.h"
#include "hil/rig_clock.h"
#include "rig_sim/device_host.h"
#include "../support/rig_process.h"

namespace adahrs::hil {
namespace {

using ::testing::HasSubstr;
namespace fm = firmware_model;

constexpr double kTimeScale = 200.0;
constexpr std::chrono::milliseconds kPollWait{200};
// Simulated seconds of the zero-loss stream: 40,000 packets per unit.
constexpr double kStreamWindowS = 400.0;
// An ADS raw data frame (docs/unit-protocol.md): header, payload, CRC.
constexpr double kSmallestPacketBytes =
    fm::kFrameHeaderBytes + fm::kAdsRawPayloadBytes + fm::kFrameTrailerBytes;

const UnitEntry& Unit(const Station& station, const std::string& role) {
  for (const UnitEntry& u : station.units) {
    if (u.role == role) return u;
  }
  throw std::runtime_error("no unit " + role);
}

TEST(UnitLink, IdentifiesEachUnitAsTheRigNamesIt) {
  testing::RigProcess rig(kTimeScale);
  const Station station = Station::Load(rig.WriteStation());
  ScaledClock clock(kTimeScale);
  for (const nlohmann::json& unit : rig.manifest()["units"]) {
    const UnitEntry& entry = Unit(station, unit["role"]);
    UnitLink link(entry, clock);
    const fm::IdentifyInfo info = link.Identify();
    EXPECT_EQ(UnitSerialText(entry.kind, info.serial_number), unit["serial"].get<std::string>());
    EXPECT_TRUE(std::filesystem::exists(rig.dir() / unit["truth"].get<std::string>()));
    // The rig's units start uncalibrated (docs/rig.md): raw mode, TAG 0, no constants.
    EXPECT_EQ(info.mode, 0);
    EXPECT_EQ(info.tag, 0);
    EXPECT_FALSE(info.constants_valid);
  }
}

TEST(UnitLink, TagChangeIsCarriedByEveryLaterPacket) {
  testing::RigProcess rig(kTimeScale);
  const Station station = Station::Load(rig.WriteStation());
  ScaledClock clock(kTimeScale);
  UnitLink link(Unit(station, "imu1"), clock);
  link.SetTag(42);
  link.Poll(kPollWait);  // packets sent before the ACK may still carry TAG 0
  std::vector<ReceivedPacket> packets = link.Poll(kPollWait);
  ASSERT_FALSE(packets.empty());
  for (const ReceivedPacket& p : packets) EXPECT_EQ(p.tag, 42);
  EXPECT_TRUE(std::holds_alternative<fm::ImuDataPayload>(packets.front().data));
  link.SetTag(0);
  link.Poll(kPollWait);
  packets = link.Poll(kPollWait);
  ASSERT_FALSE(packets.empty());
  for (const ReceivedPacket& p : packets) EXPECT_EQ(p.tag, 0);
}

TEST(UnitLink, BlockWrittenIsReadBack) {
  testing::RigProcess rig(kTimeScale);
  const Station station = Station::Load(rig.WriteStation());
  ScaledClock clock(kTimeScale);
  UnitLink link(Unit(station, "imu2"), clock);
  // A cross-axis gyro matrix other than the unit's power-on content: 1.01 on the diagonal, a small
  // off-diagonal term, exported to the target's block words by the host exporter.
  fm::ImuCalibrationConstants constants;
  for (int i = 0; i < 3; ++i) {
    constants.ca_mps2_per_g[i][i] = 9.80665;
    constants.cg[i][i] = 1.01;
  }
  constants.cg[0][1] = 0.003;
  const fm::ImuConstants exported = fm::ExportImuConstants(constants).constants;
  std::array<int16_t, fm::kImuMaxBlockWords> words{};
  uint8_t count = 0;
  ASSERT_EQ(fm::ImuConstantsReadBlock(&exported, fm::kImuBlockCg, words.data(), words.size(), &count),
            fm::ConstantsStatus::kOk);
  const std::vector<int16_t> written(words.begin(), words.begin() + count);
  link.WriteBlock(fm::kImuBlockCg, written);
  EXPECT_EQ(link.ReadBlock(fm::kImuBlockCg), written);
  // Nothing was dropped while the requests waited: the packets are all there, none lost.
  EXPECT_FALSE(link.Poll(kPollWait).empty());
  EXPECT_EQ(link.lost_packets(), 0u);
}

TEST(UnitLink, StreamsAtOneHundredHertzWithoutLossInLockstepForSimulatedMinutes) {
  // In lockstep the rig waits for these readers, so the assertions hold on a loaded machine.
  testing::RigProcess rig(kTimeScale, std::nullopt, /*lockstep=*/true);
  const Station station = Station::Load(rig.WriteStation());
  ASSERT_FALSE(station.clock_file.empty());
  const RigClock clock(station.clock_file);
  std::vector<std::unique_ptr<UnitLink>> links;
  for (const UnitEntry& entry : station.units) {
    links.push_back(std::make_unique<UnitLink>(entry, clock));
  }
  // Discard the start: until the rig has seen a link read, its port counts as unread and the
  // rig drops what it sends there (a line with no listener), which shows as a gap.
  const auto warm_up_end = std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
  while (std::chrono::steady_clock::now() < warm_up_end) {
    for (auto& link : links) link->Poll(std::chrono::milliseconds(1));
  }
  std::vector<uint64_t> lost_before, bad_crc_before;
  for (auto& link : links) {
    lost_before.push_back(link->lost_packets());
    bad_crc_before.push_back(link->decoder_counters().bad_crc);
  }
  std::vector<size_t> counts(links.size(), 0);
  const double rig_start_s = clock.RigTimeS();
  const auto wall_limit = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (clock.RigTimeS() - rig_start_s < kStreamWindowS) {
    ASSERT_LT(std::chrono::steady_clock::now(), wall_limit) << "the rig's clock hardly moves";
    for (size_t i = 0; i < links.size(); ++i) {
      counts[i] += links[i]->Poll(std::chrono::milliseconds(1)).size();
    }
  }
  const double rig_elapsed_s = clock.RigTimeS() - rig_start_s;
  for (size_t i = 0; i < links.size(); ++i) {
    SCOPED_TRACE(station.units[i].role);
    EXPECT_EQ(links[i]->lost_packets(), lost_before[i]);
    EXPECT_EQ(links[i]->decoder_counters().bad_crc, bad_crc_before[i]);
    // 100 Hz (docs/unit-protocol.md §1) over the rig's own elapsed time. At each edge of the
    // window the packets sent but not yet read are at most what lockstep lets wait: the budget,
    // the pty's queue and one look's frames (rig_sim/device_host.h), in the smallest packets.
    const double edge_packets =
        static_cast<double>(rig_sim::kLockstepBudgetBytes + rig_sim::kPtyQueueBytes) /
            kSmallestPacketBytes +
        rig_sim::kLockstepCheckFrames + 1;
    EXPECT_NEAR(static_cast<double>(counts[i]), 100.0 * rig_elapsed_s, 2.0 * edge_packets);
  }
}

TEST(UnitLink, SilentUnitGivesNoPacketsAndNoReplyNamingRoleAndCommand) {
  // In lockstep, on the rig's clock, a silence is measured on the units' own timeline and the
  // gap is counted past the 8-bit counter's wrap.
  testing::RigProcess rig(kTimeScale, std::nullopt, /*lockstep=*/true);
  const Station station = Station::Load(rig.WriteStation());
  const RigClock clock(station.clock_file);
  // The ports this test does not read hold the clock until they count as unread.
  std::this_thread::sleep_for(std::chrono::duration<double>(rig_sim::kLockstepStallLimit_s + 1.0));
  UnitLink link(Unit(station, "imu2"), clock);
  link.Identify();
  ASSERT_EQ(rig.Control("fault imu2 silent on"), "OK imu2 silent on");
  const double silence_start_s = clock.RigTimeS();  // and began before this
  // What the rig had already sent still arrives (in lockstep at most the budget and the pty's
  // queue, docs/rig.md "Time"); then the line goes quiet.
  const auto drain_end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!link.Poll(std::chrono::milliseconds(50)).empty()) {
    ASSERT_LT(std::chrono::steady_clock::now(), drain_end) << "imu2 keeps sending while silent";
  }
  EXPECT_TRUE(link.Poll(kPollWait).empty());
  try {
    link.Identify();
    FAIL() << "IDENTIFY of a silent unit returned";
  } catch (const InstrumentError& e) {
    EXPECT_EQ(e.kind(), InstrumentError::Kind::kNoReply);
    EXPECT_THAT(e.what(), HasSubstr("imu2 on " + rig.Port("imu2")));
    EXPECT_THAT(e.what(), HasSubstr("IDENTIFY"));
    EXPECT_THAT(e.what(), HasSubstr("3 attempts"));
  }
  // Plugged back in, the unit answers again and the gap shows in the sequence counter.
  const double silence_end_s = clock.RigTimeS();  // the silence ends after this
  ASSERT_EQ(rig.Control("fault imu2 silent off"), "OK imu2 silent off");
  EXPECT_EQ(link.Identify().serial_number, 2u);
  link.Poll(kPollWait);
  // The gap is counted past the counter's wrap: at least the silence less what was still in the
  // line, less the quiet margin (10 s, hil/drivers/unit_link.cc) and one turn of the counter; at
  // most the whole time since the silence began. The 8-bit counter alone says less than 256.
  const double in_line_packets =
      static_cast<double>(rig_sim::kLockstepBudgetBytes + rig_sim::kPtyQueueBytes) /
          (fm::kFrameHeaderBytes + fm::kImuRawPayloadBytes + fm::kFrameTrailerBytes) +
      rig_sim::kLockstepCheckFrames;
  ASSERT_GT(silence_end_s - silence_start_s, 30.0);
  EXPECT_GT(static_cast<double>(link.lost_packets()),
            100.0 * (silence_end_s - silence_start_s - 10.0) - in_line_packets - 256.0);
  EXPECT_LT(static_cast<double>(link.lost_packets()),
            100.0 * (clock.RigTimeS() - silence_start_s) + 2.0);
}

TEST(UnitLink, CalibratedModeWithoutConstantsIsRefusedWithTheNakReason) {
  testing::RigProcess rig(kTimeScale);
  const Station station = Station::Load(rig.WriteStation());
  ScaledClock clock(kTimeScale);
  UnitLink link(Unit(station, "imu1"), clock);
  try {
    link.SetImuMode(fm::ImuCompensationMode::kFullyCalibrated);
    FAIL() << "an uncalibrated unit accepted a calibrated mode";
  } catch (const InstrumentError& e) {
    EXPECT_EQ(e.kind(), InstrumentError::Kind::kRefused);
    EXPECT_EQ(e.role(), "imu1");
    EXPECT_THAT(e.command(), HasSubstr("SET_MODE 3"));
    EXPECT_THAT(e.what(), HasSubstr(fm::ResultCodeName(fm::ResultCode::kNoValidConstants)));
  }
}

TEST(UnitLink, UnitOfTheOtherKindIsAWrongIdentity) {
  testing::RigProcess rig(kTimeScale);
  const Station station = Station::Load(rig.WriteStation());
  ScaledClock clock(kTimeScale);
  UnitEntry wrong = Unit(station, "ads1");
  wrong.kind = UnitKind::kImu;  // the station claims an IMU on the ADS unit's port
  UnitLink link(wrong, clock);
  try {
    link.Identify();
    FAIL() << "an ADS unit passed as an IMU";
  } catch (const InstrumentError& e) {
    EXPECT_EQ(e.kind(), InstrumentError::Kind::kWrongIdentity);
    EXPECT_EQ(e.role(), "ads1");
  }
}

}  // namespace
}  // namespace adahrs::hil
