// The same OpenStation path drives ports made by an outside process: two roles reach the rig
// through `socat` pty relays, so the drivers see pseudo-terminals that neither the rig nor the
// pipeline created.
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "driver_test_util.h"
#include "hil/drivers/unit_serial.h"

extern char** environ;

namespace adahrs::hil {
namespace {

// `socat pty,raw,echo=0,link=LINK TARGET,raw,echo=0`: a new pty whose slave is LINK, relayed to the
// rig's pty slave TARGET. SIGTERM and wait on destruction.
class SocatRelay {
 public:
  SocatRelay(const std::string& link, const std::string& target) {
    std::vector<std::string> args = {
        "/usr/bin/socat", "pty,raw,echo=0,link=" + link, target + ",raw,echo=0"};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, argv[0], nullptr, nullptr, argv.data(), environ) != 0) {
      throw std::runtime_error("cannot start socat");
    }
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!std::filesystem::exists(link)) {
      if (std::chrono::steady_clock::now() > end) throw std::runtime_error("socat made no " + link);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  ~SocatRelay() {
    ::kill(pid_, SIGTERM);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
  SocatRelay(const SocatRelay&) = delete;
  SocatRelay& operator=(const SocatRelay&) = delete;

 private:
  pid_t pid_ = -1;
};

TEST(SocatRelay, OpenStationDrivesPortsMadeByAnOutsideProcess) {
  testing::RigProcess rig(test::kTimeScale);
  const std::filesystem::path table_link = rig.dir() / "x_rate_table";
  const std::filesystem::path unit_link = rig.dir() / "x_imu1";
  const std::string table_pts = rig.manifest()["ports"]["rate_table"];
  const std::string unit_pts = rig.manifest()["ports"]["imu1"];
  SocatRelay table_relay(table_link, table_pts);
  SocatRelay unit_relay(unit_link, unit_pts);
  const Station station = Station::Load(rig.WriteStation("socat.json", [&](nlohmann::json& j) {
    j["instruments"]["rate_table"]["port"]["path"] = table_link.string();
    j["units"][0]["port"]["path"] = unit_link.string();
  }));
  ASSERT_EQ(station.units[0].role, "imu1");
  ScaledClock clock(test::kTimeScale);
  StationInstruments instruments = OpenStation(station, clock);

  instruments.rate_table->CommandRate(-60.0, 100.0);
  ASSERT_TRUE(test::WaitUntil(clock, [&] { return instruments.rate_table->AtRate(); }));
  EXPECT_NEAR(instruments.rate_table->ReadRateDps(), -60.0, 0.01 + 60.0 * 1e-5);

  UnitLink& imu1 = *instruments.units[0];
  EXPECT_EQ(UnitSerialText(imu1.entry().kind, imu1.Identify().serial_number),
            rig.manifest()["units"][0]["serial"].get<std::string>());
  imu1.SetTag(7);
  imu1.Poll(std::chrono::milliseconds(100));
  // 5,000 packets (50 simulated s, 0.25 s wall at 200x on a quiet machine) through the relay, none
  // lost. The count, not a wall-time window, ends the loop: a loaded machine (a sanitizer build, a
  // parallel compile) only takes longer; 20 s of wall time is the limit for a relay that stalls.
  size_t packets = 0;
  const auto limit = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (packets <= 5000u && std::chrono::steady_clock::now() < limit) {
    for (const ReceivedPacket& p : imu1.Poll(std::chrono::milliseconds(10))) {
      EXPECT_EQ(p.tag, 7);
      ++packets;
    }
  }
  EXPECT_GT(packets, 5000u);
  EXPECT_EQ(imu1.lost_packets(), 0u);
}

}  // namespace
}  // namespace adahrs::hil
