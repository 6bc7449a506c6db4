// UnitLink against the virtual rig as a separate process (tests/support/rig_process.h): every
// request of the unit protocol, the TAG in the packets, zero loss over simulated minutes, and the
// faults the executor must report (a silent unit, a NAK, a unit of the wrong kind).
// Runs alone (SERIAL in tests/CMakeLists.txt): the silent-unit test times its drain on the wall
// clock.
#include "hil/drivers/unit_link.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <future>
#include <thread>

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include "../support/rig_process.h"
#include "firmware_model/constants_exporter.h"
#include "hil/drivers/unit_serial.h"
#include "hil/rig_clock.h"

namespace adahrs::hil {
namespace {

using ::testing::HasSubstr;
namespace fm = firmware_model;

constexpr double kTimeScale = 200.0;
constexpr std::chrono::milliseconds kPollWait{200};
// Simulated seconds of the zero-loss stream: 40,000 packets per unit.
constexpr double kStreamWindowS = 400.0;

const UnitEntry& Unit(const Station& station, const std::string& role) {
  for (const UnitEntry& u : station.units) {
    if (u.role == role) return u;
  }
  throw std::runtime_error("no unit " + role);
}

// Sends `line` and "time" in one write on the rig's control port, so the rig acts on both in the
// same frame; checks the first reply and returns the frame's time (simulated s).
double ControlAt(const testing::RigProcess& rig,
                 const std::string& line,
                 const std::string& expected_reply) {
  const int fd = ::open(rig.Port("control").c_str(), O_RDWR | O_NOCTTY);
  if (fd < 0) throw std::runtime_error("cannot open the control port");
  termios tio{};
  ::tcgetattr(fd, &tio);
  ::cfmakeraw(&tio);
  ::tcsetattr(fd, TCSANOW, &tio);
  ::tcflush(fd, TCIFLUSH);
  const std::string out = line + "\ntime\n";
  const bool written = ::write(fd, out.data(), out.size()) == static_cast<ssize_t>(out.size());
  std::vector<std::string> replies(1);
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (written && replies.size() < 3 && std::chrono::steady_clock::now() < end) {
    pollfd p{fd, POLLIN, 0};
    char c = 0;
    if (::poll(&p, 1, 10) <= 0 || ::read(fd, &c, 1) != 1) continue;
    if (c == '\n') {
      replies.emplace_back();
    } else if (c != '\r') {
      replies.back() += c;
    }
  }
  ::close(fd);
  EXPECT_EQ(replies[0], expected_reply);
  if (replies.size() < 3 || replies[1].rfind("OK ", 0) != 0) {
    throw std::runtime_error("no time from the control port after '" + line + "'");
  }
  return std::stod(replies[1].substr(3));
}

TEST(UnitLink, IdentifiesEachUnitAsTheRigNamesIt) {
  testing::RigProcess rig(kTimeScale);
  const Station station = Station::Load(rig.WriteStation());
  ScaledClock clock(kTimeScale);
  for (const nlohmann::json& unit : rig.manifest()["units"]) {
    const UnitEntry& entry = Unit(station, unit["role"]);
    UnitLink link(entry, clock);
    const hil::IdentifyInfo info = link.Identify();
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
  ASSERT_EQ(
      fm::ImuConstantsReadBlock(&exported, fm::kImuBlockCg, words.data(), words.size(), &count),
      fm::ConstantsStatus::kOk);
  const std::vector<int16_t> written(words.begin(), words.begin() + count);
  link.WriteBlock(fm::kImuBlockCg, written);
  EXPECT_EQ(link.ReadBlock(fm::kImuBlockCg), written);
  // Nothing was dropped while the requests waited: the packets are all there, none lost.
  EXPECT_FALSE(link.Poll(kPollWait).empty());
  EXPECT_EQ(link.lost_packets(), 0u);
}

// Every packet of a window of simulated minutes arrives, counted two ways: the 8-bit sequence
// counter (consecutive packets one apart: a gap shorter than a turn) and the count against the
// unit's own production, one packet per 10 ms frame of the rig's clock (docs/rig.md "Units on
// their ports"), which sees whole turns of 256 lost packets the counter cannot. The window's
// edges are the rig's own frames: each unit's line is switched on (silent fault off) and off
// again by the control port, which gives the frame it acted in.
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
  const size_t n = links.size();
  std::vector<std::vector<ReceivedPacket>> packets(n);
  std::vector<uint64_t> lost_after_first(n), bad_crc_after_first(n);
  // Polls every link once, keeping the packets of the lines `keep` says are on.
  const auto poll_all = [&](const std::vector<bool>& keep) {
    bool any = false;
    for (size_t i = 0; i < n; ++i) {
      const std::vector<ReceivedPacket> p = links[i]->Poll(std::chrono::milliseconds(1));
      any = any || !p.empty();
      if (!keep[i]) continue;
      if (packets[i].empty() && !p.empty()) {
        // The first packets after the line came on: the counter's gap over the silent stretch
        // and any bytes cut at the switch are counted by now, and not again.
        lost_after_first[i] = links[i]->lost_packets();
        bad_crc_after_first[i] = links[i]->decoder_counters().bad_crc;
      }
      packets[i].insert(packets[i].end(), p.begin(), p.end());
    }
    return any;
  };
  // A control command acts at a frame, and in lockstep the frames wait for every attached reader
  // that lags: the links are read while the command waits for its reply, or a line already on
  // could hold the clock (and so the reply) until the rig gives its reader up.
  const auto control =
      [&](const std::string& line, const std::string& reply, const std::vector<bool>& keep) {
        std::future<double> at =
            std::async(std::launch::async, [&] { return ControlAt(rig, line, reply); });
        while (at.wait_for(std::chrono::seconds(0)) != std::future_status::ready) poll_all(keep);
        return at.get();
      };
  // Reads every link until none has brought a packet for `quiet` of wall time.
  const auto drain = [&](std::chrono::milliseconds quiet, const std::vector<bool>& keep) {
    auto last = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - last < quiet) {
      if (poll_all(keep)) last = std::chrono::steady_clock::now();
    }
  };
  // Every line silent, and all that was sent before read: the window starts from empty lines.
  const std::vector<bool> none(n, false);
  for (const UnitEntry& u : station.units)
    control("fault " + u.role + " silent on", "OK " + u.role + " silent on", none);
  drain(std::chrono::milliseconds(300), none);  // 60 s of the rig's clock at 200x, nothing sent
  std::vector<double> on_s(n), off_s(n);
  std::vector<bool> on(n, false);
  for (size_t i = 0; i < n; ++i) {
    const std::string& role = station.units[i].role;
    on[i] = true;  // its first packets may come before the reply: the line was drained silent
    on_s[i] = control("fault " + role + " silent off", "OK " + role + " silent off", on);
  }
  const auto wall_limit = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (clock.RigTimeS() - on_s.back() < kStreamWindowS) {
    ASSERT_LT(std::chrono::steady_clock::now(), wall_limit) << "the rig's clock hardly moves";
    poll_all(on);
  }
  for (size_t i = 0; i < n; ++i) {
    const std::string& role = station.units[i].role;
    off_s[i] = control("fault " + role + " silent on", "OK " + role + " silent on", on);
  }
  drain(std::chrono::milliseconds(300), on);
  for (size_t i = 0; i < n; ++i) {
    SCOPED_TRACE(station.units[i].role);
    ASSERT_FALSE(packets[i].empty());
    int gaps = 0;
    for (size_t k = 1; k < packets[i].size(); ++k) {
      gaps += static_cast<uint8_t>(packets[i][k].seq - packets[i][k - 1].seq) != 1 ? 1 : 0;
    }
    EXPECT_EQ(gaps, 0) << "the sequence counter skips";
    EXPECT_EQ(links[i]->lost_packets(), lost_after_first[i]);
    EXPECT_EQ(links[i]->decoder_counters().bad_crc, bad_crc_after_first[i]);
    // One packet per frame the line was on. Each switch acts at a frame boundary, and a raw
    // packet leaves within its own frame (under 6 ms of the 10 at 115,200 baud), so no packet is
    // cut at either edge: the count is exact.
    const double frames_on = std::round((off_s[i] - on_s[i]) / 0.01);
    std::printf("%s: %zu packets over %.0f frames on (%.2f ... %.2f s)\n",
                station.units[i].role.c_str(),
                packets[i].size(),
                frames_on,
                on_s[i],
                off_s[i]);
    EXPECT_EQ(static_cast<double>(packets[i].size()), frames_on);
  }
}

TEST(UnitLink, SilentUnitGivesNoPacketsAndNoReplyNamingRoleAndCommand) {
  testing::RigProcess rig(kTimeScale);
  const Station station = Station::Load(rig.WriteStation());
  ScaledClock clock(kTimeScale);
  UnitLink link(Unit(station, "imu2"), clock);
  link.Identify();
  link.Poll(kPollWait);
  const uint64_t lost_before = link.lost_packets();
  const double silent_from_s = ControlAt(rig, "fault imu2 silent on", "OK imu2 silent on");
  // What the rig had already sent still arrives (its per-port backlog, docs/rig.md "Time");
  // then the line goes quiet.
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
  // Plugged back in, the unit answers again and the gap shows in the sequence counter: the
  // frames it was silent for, modulo the 8-bit counter's 256, give or take the packet cut at
  // each edge.
  const double silent_to_s = ControlAt(rig, "fault imu2 silent off", "OK imu2 silent off");
  EXPECT_EQ(link.Identify().serial_number, 2u);
  link.Poll(kPollWait);
  const auto missed = static_cast<int64_t>(std::lround((silent_to_s - silent_from_s) / 0.01));
  const auto counted = static_cast<int64_t>(link.lost_packets() - lost_before);
  const int64_t off_by = ((counted - missed) % 256 + 256 + 128) % 256 - 128;
  EXPECT_LE(std::abs(off_by), 2) << "missed " << missed << " frames, counted " << counted;
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
    EXPECT_THAT(e.what(), HasSubstr(hil::ResultCodeName(fm::ResultCode::kNoValidConstants)));
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
