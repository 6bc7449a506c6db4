// UnitLink against the virtual rig as a separate process (tests/support/rig_process.h): every
// request of the unit protocol, the TAG in the packets, zero loss over simulated minutes, and the
// faults the executor must report (a silent unit, a NAK, a unit of the wrong kind).
// ctest: RUN_SERIAL — the zero-loss stream is timed against the rig's wall clock: with light tests
// beside it on 2 cores the rig fell a third behind real time once and the test lost packets.
#include "hil/drivers/unit_link.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "firmware_model/constants_exporter.h"
#include "hil/drivers/unit_serial.h"
#include "../support/rig_process.h"

namespace adahrs::hil {
namespace {

using ::testing::HasSubstr;
namespace fm = firmware_model;

constexpr double kTimeScale = 200.0;
constexpr std::chrono::milliseconds kPollWait{200};

const UnitEntry& Unit(const Station& station, const std::string& role) {
  for (const UnitEntry& u : station.units) {
    if (u.role == role) return u;
  }
  throw std::runtime_error("no unit " + role);
}

// Reads the rig's simulated clock from its control port ("OK <seconds>").
double RigTimeS(const testing::RigProcess& rig) {
  const std::string reply = rig.Control("time");
  return std::stod(reply.substr(3));
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

TEST(UnitLink, StreamsAtOneHundredHertzWithoutLossForSimulatedMinutes) {
  testing::RigProcess rig(kTimeScale);
  const Station station = Station::Load(rig.WriteStation());
  ScaledClock clock(kTimeScale);
  std::vector<std::unique_ptr<UnitLink>> links;
  for (const UnitEntry& entry : station.units) {
    links.push_back(std::make_unique<UnitLink>(entry, clock));
  }
  for (auto& link : links) link->Poll(std::chrono::milliseconds(1));  // discard the start
  std::vector<size_t> counts(links.size(), 0);
  const double rig_start_s = RigTimeS(rig);
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (std::chrono::steady_clock::now() < end) {
    for (size_t i = 0; i < links.size(); ++i) {
      counts[i] += links[i]->Poll(std::chrono::milliseconds(1)).size();
    }
  }
  const double rig_elapsed_s = RigTimeS(rig) - rig_start_s;
  ASSERT_GT(rig_elapsed_s, 60.0);  // 2 s wall at 200x: simulated minutes even on a loaded machine
  for (size_t i = 0; i < links.size(); ++i) {
    SCOPED_TRACE(station.units[i].role);
    EXPECT_EQ(links[i]->lost_packets(), 0u);
    EXPECT_EQ(links[i]->decoder_counters().bad_crc, 0u);
    // 100 Hz (docs/unit-protocol.md §1) over the rig's own elapsed time. The window edges are a
    // control-port round trip each plus the packets still in the pty at the end, ~10 ms wall
    // each = 2 simulated s at 200x = 200 packets: 1 % of the ~40,000 expected.
    EXPECT_NEAR(static_cast<double>(counts[i]), 100.0 * rig_elapsed_s, 0.01 * 100.0 * rig_elapsed_s);
  }
}

TEST(UnitLink, SilentUnitGivesNoPacketsAndNoReplyNamingRoleAndCommand) {
  testing::RigProcess rig(kTimeScale);
  const Station station = Station::Load(rig.WriteStation());
  ScaledClock clock(kTimeScale);
  UnitLink link(Unit(station, "imu2"), clock);
  link.Identify();
  ASSERT_EQ(rig.Control("fault imu2 silent on"), "OK imu2 silent on");
  // What the rig had already sent still arrives (its per-port backlog holds up to ~2.5 s wall,
  // docs/rig.md "Time"); then the line goes quiet.
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
  ASSERT_EQ(rig.Control("fault imu2 silent off"), "OK imu2 silent off");
  EXPECT_EQ(link.Identify().serial_number, 2u);
  link.Poll(kPollWait);
  EXPECT_GT(link.lost_packets(), 0u);
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
