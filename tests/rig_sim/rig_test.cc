// The whole rig in-process, reached only through its pseudo-terminals, as a client would.
#include "rig_sim/rig.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "firmware_model/constants_exporter.h"
#include "firmware_model/unit_firmware.h"
#include "hil/codecs/modbus_rtu.h"
#include "hil/codecs/unit_protocol_client.h"
#include "tests/firmware_model/realistic_constants.h"
#include "tests/rig_sim/pty_client.h"

namespace adahrs::rig_sim {
namespace {

namespace fm = firmware_model;
using ::testing::HasSubstr;
using testing::PtyClient;
using ::testing::StartsWith;

std::filesystem::path TempRunDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("adahrs_rig_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir;
}

// One IMU and one ADS, no instruments: enough for port behaviour and cheap on 2 cores.
RigConfig SmallConfig(double time_scale, bool lockstep = false) {
  nlohmann::json j = DefaultRigConfig();
  j["time_scale"] = time_scale;
  j["lockstep"] = lockstep;
  j["units"]["imu"] = {j["units"]["imu"][0]};
  j["instruments"] = nlohmann::json::object();
  return RigConfig::FromJson(j, "small rig");
}

struct Stream {
  std::vector<fm::Frame> data;
  std::vector<hil::MaintenanceResponse> responses;
  fm::DecoderCounters counters{};
  uint64_t lost = 0;
};

Stream Decode(const std::vector<uint8_t>& bytes) {
  hil::StreamReader reader;
  hil::SequenceTracker tracker;
  Stream s;
  for (const fm::Frame& f : reader.Push(bytes)) {
    if (f.type == static_cast<uint8_t>(fm::PacketType::kMaintenanceResponse)) {
      s.responses.push_back(hil::ParseMaintenanceResponse(f));
    } else {
      s.data.push_back(f);
      tracker.Observe(f.sequence);
    }
  }
  s.counters = reader.counters();
  s.lost = tracker.lost_total();
  return s;
}

TEST(Rig, WritesManifestLinksAndTruthAndStreamsUnitsOnPtys) {
  const auto dir = TempRunDir("manifest");
  nlohmann::json j = DefaultRigConfig();
  j["time_scale"] = 20.0;
  j["lockstep"] = true;  // the world waits for this test's reader, however loaded the machine
  Rig rig(RigConfig::FromJson(j, "default"), dir);
  rig.Start(dir / "manifest.json");

  std::ifstream in(dir / "manifest.json");
  const nlohmann::json manifest = nlohmann::json::parse(in);
  EXPECT_EQ(manifest["format"], "adahrs-rig-manifest");
  EXPECT_EQ(manifest["version"], kManifestVersion);
  for (const std::string role : {"imu1", "imu2", "imu3", "imu4", "ads1", "control"}) {
    const std::string path = manifest["ports"][role];
    EXPECT_THAT(path, StartsWith("/dev/pts/")) << role;
    EXPECT_EQ(std::filesystem::read_symlink(dir / "ports" / role), path) << role;
    EXPECT_EQ(manifest["links"][role], (dir / "ports" / role).string());
  }
  for (const std::string serial : {"IMU-0001", "IMU-0004", "ADS-0001"}) {
    std::ifstream truth(dir / "truth" / (serial + ".json"));
    ASSERT_TRUE(truth.good()) << serial;
    EXPECT_EQ(nlohmann::json::parse(truth)["serial"], serial);
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "manifest.json.tmp"));

  // Through the stable link, as a station file would name it: 100 Hz packets at 20x.
  // The line is closed before the control commands below: in lockstep an open line left unread
  // would hold the frames those commands act at.
  {
    PtyClient imu4((dir / "ports" / "imu4").string());
    imu4.Drain();
    const double from_s = rig.host().now_s();
    std::vector<uint8_t> bytes;
    imu4.ReadFor(1.0, bytes);
    const double to_s = rig.host().now_s();
    const Stream s = Decode(bytes);
    // 100 packets per simulated second (≈ 2,000 in 1 s wall at 20x on an idle machine), less what
    // lockstep lets wait unread: the budget and the pty's queue (≈ 400 packets).
    EXPECT_GT(to_s - from_s, 1.0);
    EXPECT_GE(static_cast<double>(s.data.size()), 100.0 * (to_s - from_s) - 450.0);
    EXPECT_EQ(s.lost, 0u);
    EXPECT_EQ(s.counters.bad_crc, 0u);
  }
  PtyClient control(manifest["ports"]["control"].get<std::string>());
  EXPECT_THAT(control.Command("time"), StartsWith("OK "));
  EXPECT_THAT(control.Command("status"), HasSubstr("imu1,imu2,imu3,imu4,ads1,control faults=none"));
  EXPECT_EQ(control.Command("orientation imu2 12"), "OK imu2 12");
  EXPECT_EQ(rig.host().environment().imu_orientation[1], 12);
  EXPECT_EQ(control.Command("orientation ads1 12"), "ERR ads1 is not an IMU unit");
  EXPECT_THAT(control.Command("fault imu9 silent on"), StartsWith("ERR no role 'imu9'"));
  EXPECT_EQ(control.Command("faults imu1"),
            "OK silent garbage drop_rate corrupt_rate unplugged reset");
  EXPECT_THAT(control.Command("launch"), StartsWith("ERR unknown command"));
  rig.Stop();
  std::filesystem::remove_all(dir);
}

TEST(Rig, MaintenanceCommandsOverThePty) {
  const auto dir = TempRunDir("maintenance");
  Rig rig(SmallConfig(10.0), dir);
  rig.Start(dir / "manifest.json");
  PtyClient port(rig.ports().at("imu1"));
  hil::UnitProtocolClient client;
  // Sends a request and returns the response (data packets around it are skipped).
  auto ask = [&](const std::vector<uint8_t>& request) {
    port.Drain();
    port.Write(request);
    std::vector<uint8_t> bytes;
    for (int i = 0; i < 100; ++i) {
      port.ReadFor(0.02, bytes);
      const Stream s = Decode(bytes);
      if (!s.responses.empty()) return s.responses.front();
    }
    ADD_FAILURE() << "no response";
    return hil::MaintenanceResponse{};
  };
  const hil::IdentifyInfo id = hil::ParseIdentify(ask(client.Identify()));
  EXPECT_EQ(id.unit_kind, fm::UnitKind::kImu);
  EXPECT_EQ(id.serial_number, 1u);
  EXPECT_EQ(ask(client.SetTag(77)).result, fm::ResultCode::kAck);
  EXPECT_EQ(ask(client.SetImuMode(fm::ImuCompensationMode::kThermal)).result,
            fm::ResultCode::kNoValidConstants);
  std::vector<uint8_t> bytes;
  port.ReadFor(0.2, bytes);
  const Stream tagged = Decode(bytes);
  ASSERT_FALSE(tagged.data.empty());
  EXPECT_EQ(tagged.data.back().tag, 77);
  EXPECT_EQ(hil::ParseReadBlock(ask(client.ReadBlock(fm::kImuBlockCa))).words.size(),
            fm::kImuMatrixBlockWords);
  // A full constant set written block by block, committed, then a compensated mode.
  const fm::ImuConstants constants = fm::ExportImuConstants(fm::testing::RealisticImu(8)).constants;
  for (uint8_t block = fm::kImuBlockThermalFirst; block <= fm::kImuBlockCg; ++block) {
    int16_t words[fm::kImuMaxBlockWords];
    uint8_t count = 0;
    fm::ImuConstantsReadBlock(&constants, block, words, fm::kImuMaxBlockWords, &count);
    ASSERT_EQ(ask(client.WriteBlock(block, {words, count})).result, fm::ResultCode::kAck);
  }
  EXPECT_EQ(hil::ParseCommit(ask(client.Commit())).constants_version, 1);
  EXPECT_EQ(ask(client.SetImuMode(fm::ImuCompensationMode::kSensorCalibrated)).result,
            fm::ResultCode::kAck);
  bytes.clear();
  port.ReadFor(0.2, bytes);
  EXPECT_EQ(hil::ParseImuData(Decode(bytes).data.back()).mode,
            fm::ImuCompensationMode::kSensorCalibrated);
  EXPECT_EQ(ask(client.Reset()).result, fm::ResultCode::kAck);
  bytes.clear();
  port.ReadFor(0.2, bytes);
  EXPECT_EQ(Decode(bytes).data.back().tag, 0);
  EXPECT_EQ(hil::ParseImuData(Decode(bytes).data.back()).mode, fm::ImuCompensationMode::kRaw);
  // The committed set survived the power cycle: the calibrated mode is accepted again.
  EXPECT_TRUE(hil::ParseIdentify(ask(client.Identify())).constants_valid);
  rig.Stop();
  std::filesystem::remove_all(dir);
}

// The first `count` packets of imu1 from the start of the rig, read through the pty.
std::vector<uint8_t> FirstPackets(double time_scale, size_t count) {
  const auto dir = TempRunDir("timeline");
  Rig rig(SmallConfig(time_scale), dir);
  PtyClient port(rig.ports().at("imu1"));
  rig.Start(dir / "manifest.json");
  std::vector<uint8_t> bytes;
  const size_t packet_bytes = 51;  // raw IMU packet (docs/unit-protocol.md §4.2: 43 + 8)
  EXPECT_TRUE(port.ReadAtLeast(count * packet_bytes, 10.0, bytes));
  rig.Stop();
  std::filesystem::remove_all(dir);
  bytes.resize(std::min(bytes.size(), count * packet_bytes));
  return bytes;
}

TEST(Rig, SameSimulatedTimelineAtTimeScaleOneAndTwoHundred) {
  // 100 packets = 1 s simulated: 1 s wall at 1x, 5 ms at 200x. Sample k's packet holds the
  // physics at t = k · 10 ms with the noise stream of that instant: byte-identical streams mean the
  // same sequence numbers, TAGs and values at the same simulated times.
  const std::vector<uint8_t> real_time = FirstPackets(1.0, 100);
  const std::vector<uint8_t> fast = FirstPackets(200.0, 100);
  ASSERT_EQ(real_time.size(), 5100u);
  EXPECT_EQ(real_time, fast);
  const Stream s = Decode(fast);
  ASSERT_EQ(s.data.size(), 100u);
  EXPECT_EQ(s.data.back().sequence, 99);
}

TEST(Rig, ByteAndPhysicalFaultsAreSeenByTheClient) {
  const auto dir = TempRunDir("faults");
  // Lockstep: what the rig released before a command is bounded by the budget, so the pre-read
  // below drains it however loaded the machine (free-running, a slow reader's backlog could hold
  // seconds of packets from before the fault).
  Rig rig(SmallConfig(50.0, /*lockstep=*/true), dir);
  rig.Start(dir / "manifest.json");
  PtyClient control(rig.ports().at("control"));
  PtyClient port(rig.ports().at("imu1"));
  // Reads 0.3 s wall (15 s simulated, ~1,500 packets) after `command` took effect. Bytes released
  // before it (the host's backlog for this client, which did not read in between) are read and
  // discarded first.
  auto observe = [&](const std::string& command) {
    std::vector<uint8_t> before;
    if (!command.empty()) {
      // The command acts at a frame, and in lockstep frames wait for this unread line once its
      // backlog passes the budget: the line is read while the reply is awaited.
      std::future<std::string> reply =
          std::async(std::launch::async, [&] { return control.Command(command); });
      while (reply.wait_for(std::chrono::milliseconds(0)) != std::future_status::ready) {
        port.ReadFor(0.005, before);
      }
      EXPECT_THAT(reply.get(), StartsWith("OK")) << command;
    }
    port.ReadFor(0.2, before);
    std::vector<uint8_t> bytes;
    port.ReadFor(0.3, bytes);
    return bytes;
  };
  // 0.3 s wall at 50x is ~1,500 packets; the bounds below allow a loaded machine a fifth of that
  // and compare fault effects with what was received.
  const Stream clean = Decode(observe(""));
  EXPECT_GT(clean.data.size(), 300u);
  EXPECT_EQ(clean.counters.bad_crc, 0u);

  EXPECT_TRUE(observe("fault imu1 silent on").empty());
  EXPECT_GT(Decode(observe("fault imu1 silent off")).data.size(), 300u);

  const std::vector<uint8_t> garbage = observe("fault imu1 garbage on");
  EXPECT_GT(garbage.size(), 300u * 51u);       // bytes keep coming …
  EXPECT_EQ(Decode(garbage).data.size(), 0u);  // … but no frame survives
  observe("fault imu1 garbage off");

  // 1 % of bytes dropped: a 51-byte packet survives with probability 0.99^51 = 60 %, so about
  // 0.67 packets are lost per packet received; a quarter of that is a safe lower bound.
  const Stream dropped = Decode(observe("fault imu1 drop_rate 0.01"));
  EXPECT_GT(dropped.data.size(), 100u);
  EXPECT_GT(dropped.lost, dropped.data.size() / 4);
  observe("fault imu1 drop_rate 0");
  // 1 % of bytes with a flipped bit: ~40 % of the packets fail their CRC (0.67 per good one).
  const Stream corrupted = Decode(observe("fault imu1 corrupt_rate 0.01"));
  EXPECT_GT(corrupted.data.size(), 100u);
  EXPECT_GT(corrupted.counters.bad_crc, corrupted.data.size() / 4);
  EXPECT_GT(corrupted.lost, corrupted.data.size() / 4);
  EXPECT_THAT(control.Command("status"), HasSubstr("faults=imu1:corrupt_rate=0.01"));
  observe("fault imu1 corrupt_rate 0");

  EXPECT_TRUE(observe("fault imu1 unplugged on").empty());
  const Stream replugged = Decode(observe("fault imu1 unplugged off"));
  ASSERT_FALSE(replugged.data.empty());

  EXPECT_TRUE(observe("fault imu1 reset on").empty());
  const Stream powered = Decode(observe("fault imu1 reset off"));
  ASSERT_FALSE(powered.data.empty());
  // Power-on restarts the sequence at 0: 0.3 s wall at 50x is < 2,560 packets, so the stream
  // holds the first packets after power-on (sequence 0, 1, …) unless the drain came late.
  EXPECT_EQ(powered.lost, 0u);
  EXPECT_EQ(powered.data.front().tag, 0);
  EXPECT_THAT(control.Command("fault imu1 on_fire on"), HasSubstr("no fault 'on_fire'"));
  rig.Stop();
  std::filesystem::remove_all(dir);
}

TEST(Rig, StartFaultsFromTheConfigAreAppliedAndCheckedAgainstTheDevices) {
  const auto dir = TempRunDir("startfaults");
  nlohmann::json j = DefaultRigConfig();
  j["units"]["imu"] = {j["units"]["imu"][0]};
  j["faults"] = {{{"role", "imu1"}, {"fault", "silent"}, {"on", true}}};
  {
    Rig rig(RigConfig::FromJson(j, "rig.json"), dir);
    EXPECT_THAT(rig.Control("status"), HasSubstr("faults=imu1:silent=on"));
  }
  j["faults"] = {{{"role", "imu1"}, {"fault", "melting"}, {"on", true}}};
  try {
    Rig rig(RigConfig::FromJson(j, "rig.json"), dir);
    FAIL();
  } catch (const common::ParamError& e) {
    EXPECT_THAT(e.what(), HasSubstr("rig.json: $.faults[0]: imu1: no fault 'melting'"));
  }
  j["faults"] = {{{"role", "rate_table9"}, {"fault", "silent"}, {"on", true}}};
  EXPECT_THROW(Rig(RigConfig::FromJson(j, "rig.json"), dir), common::ParamError);
  std::filesystem::remove_all(dir);
}

TEST(Rig, TheChamberBehindItsModbusPortWarmsTheUnits) {
  // A client writes the F4's set point (register 300, tenths of °C: protocols.md §2) over the
  // imu_chamber pty; the chamber air it drives is the IMU's air, so the unit's gyro temperature
  // counts rise (ADXRS150 TEMP +8.4 mV/K, physics.md 2.1).
  const auto dir = TempRunDir("chamber");
  nlohmann::json j = DefaultRigConfig();
  j["time_scale"] = 500.0;
  j["units"]["imu"] = {j["units"]["imu"][0]};
  j["units"]["ads"] = nlohmann::json::array();
  Rig rig(RigConfig::FromJson(j, "rig with chamber"), dir);
  rig.Start(dir / "manifest.json");
  PtyClient imu(rig.ports().at("imu1"));
  auto temp_counts = [&] {
    imu.Drain();
    std::vector<uint8_t> bytes;
    imu.ReadFor(0.05, bytes);
    const Stream s = Decode(bytes);
    EXPECT_FALSE(s.data.empty());
    return s.data.empty() ? 0 : hil::ParseImuData(s.data.back()).raw.temp_cnt[2];
  };
  const int before = temp_counts();
  PtyClient chamber(rig.ports().at("imu_chamber"));
  chamber.Write(hil::modbus::EncodeRequest(hil::modbus::WriteSingleRequest(1, 300, 600)));
  std::vector<uint8_t> reply;
  ASSERT_TRUE(chamber.ReadAtLeast(8, 5.0, reply));  // FC 06 echoes the request (8 bytes)
  EXPECT_EQ(reply, hil::modbus::EncodeRequest(hil::modbus::WriteSingleRequest(1, 300, 600)));
  // Keep reading the unit's line while waiting: a client that stops reading lets the rig's
  // backlog fill with old packets, which a later read would return first.
  std::vector<uint8_t> discarded;
  double air_c = 25.0;
  for (int i = 0; i < 200 && air_c < 40.0; ++i) {
    discarded.clear();
    imu.ReadFor(0.05, discarded);
    air_c = rig.host().environment().imu_chamber_air_c;
  }
  EXPECT_GE(air_c, 40.0);
  // 15 K warmer air: the die follows with its thermal lag; a few K already move the 16 × 12-bit
  // sum by hundreds of counts (8.4 mV/K · 13,107 counts/V ≈ 110 counts/K).
  EXPECT_GT(temp_counts(), before + 200);
  rig.Stop();
  std::filesystem::remove_all(dir);
}

TEST(Rig, TheRateTableTurnsTheUnitsOnIt) {
  // JOG 100 over the rate_table pty (ATL, docs/rig/rate-table.md); the IMU in orientation 31 has
  // z_B up, so its z gyro sees +100 °/s: ~2.1e6 counts (ADXRS150 12.5 mV/°/s, 16 summed 19-bit
  // conversions, tests/firmware_model/realistic_constants.h: 20,972 counts per °/s), while x and y
  // see only their misalignment (≤ ~2 %, 4e4 counts) and noise.
  const auto dir = TempRunDir("table");
  nlohmann::json j = DefaultRigConfig();
  j["time_scale"] = 100.0;
  j["units"]["imu"] = {j["units"]["imu"][0]};
  j["units"]["ads"] = nlohmann::json::array();
  Rig rig(RigConfig::FromJson(j, "rig with table"), dir);
  rig.Start(dir / "manifest.json");
  PtyClient imu(rig.ports().at("imu1"));
  auto gyro_counts = [&] {
    std::vector<uint8_t> bytes;
    imu.ReadFor(0.3, bytes);
    const Stream s = Decode(bytes);
    EXPECT_FALSE(s.data.empty());
    return s.data.empty() ? fm::ImuDataPayload{} : hil::ParseImuData(s.data.back());
  };
  const fm::ImuDataPayload at_rest = gyro_counts();
  PtyClient table(rig.ports().at("rate_table"));
  table.WriteText("SRV 1\r");
  table.WriteText("JOG 100\r");
  double rate_dps = 0.0;
  for (int i = 0; i < 200 && std::abs(rate_dps - 100.0) > 0.5; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    rate_dps = rig.host().environment().table_rate_dps;
  }
  EXPECT_NEAR(rate_dps, 100.0, 0.5);
  const fm::ImuDataPayload turning = gyro_counts();
  EXPECT_GT(turning.raw.gyro_cnt[2] - at_rest.raw.gyro_cnt[2], 1500000);
  EXPECT_LT(std::abs(turning.raw.gyro_cnt[0] - at_rest.raw.gyro_cnt[0]), 200000);
  EXPECT_LT(std::abs(turning.raw.gyro_cnt[1] - at_rest.raw.gyro_cnt[1]), 200000);
  rig.Stop();
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace adahrs::rig_sim
