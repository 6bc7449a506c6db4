// The unit devices driven through their SerialDevice interface on simulated time, read back by the
// PC-side codec (hil/codecs/unit_protocol_client.h, an independent CRC implementation).
#include <gtest/gtest.h>

#include "common/random.h"
#include "common/units.h"
#include "firmware_model/constants_exporter.h"
#include "firmware_model/unit_firmware.h"
#include "hil/codecs/unit_protocol_client.h"
#include "rig_sim/ads_unit_device.h"
#include "rig_sim/fixture_orientation.h"
#include "rig_sim/imu_unit_device.h"
#include "tests/firmware_model/realistic_constants.h"

namespace adahrs::rig_sim {
namespace {

namespace fm = firmware_model;

constexpr uint64_t kSeed = 4242;

ImuUnitDeviceConfig ImuConfig(int baud = 115200) {
  ImuUnitDeviceConfig c;
  c.role = "imu1";
  c.slot = 0;
  c.serial_number = 7;
  c.params = sensor_sim::ImuUnitParams::Draw("IMU-0007", kSeed, sensor_sim::ModelProfile::kTruth);
  c.noise_seed = common::Rng::Derive(kSeed, 1);
  c.baud = baud;
  return c;
}

// Runs `device` from `from_s` to `to_s` in frames of `frame_s`, feeding `request` (if any) at the
// first frame, and returns every byte it released.
std::vector<uint8_t> RunDevice(SerialDevice& device,
                               RigEnvironment& env,
                               double from_s,
                               double to_s,
                               double frame_s = 0.01,
                               const std::vector<uint8_t>& request = {}) {
  std::vector<uint8_t> out;
  bool sent = request.empty();
  for (double t = from_s + frame_s; t <= to_s + 1e-9; t += frame_s) {
    env.time_s = t;
    if (!sent) {
      device.Receive(request, t);
      sent = true;
    }
    device.Advance(t, frame_s, env);
    device.TakeOutput(t, out);
  }
  return out;
}

struct Decoded {
  std::vector<fm::Frame> data;
  std::vector<hil::MaintenanceResponse> responses;
};

Decoded Decode(const std::vector<uint8_t>& bytes) {
  hil::StreamReader reader;
  Decoded d;
  for (const fm::Frame& f : reader.Push(bytes)) {
    if (f.type == static_cast<uint8_t>(fm::PacketType::kMaintenanceResponse)) {
      d.responses.push_back(hil::ParseMaintenanceResponse(f));
    } else {
      d.data.push_back(f);
    }
  }
  return d;
}

// Sends one request and runs 50 ms; returns the (single) response.
hil::MaintenanceResponse Ask(SerialDevice& device,
                             RigEnvironment& env,
                             double& t,
                             const std::vector<uint8_t>& request) {
  const Decoded d = Decode(RunDevice(device, env, t, t + 0.05, 0.01, request));
  t += 0.05;
  EXPECT_EQ(d.responses.size(), 1u);
  return d.responses.empty() ? hil::MaintenanceResponse{} : d.responses.front();
}

TEST(ImuUnitDevice, Streams100HzPacketsWithConsecutiveSequenceNumbers) {
  ImuUnitDevice device(ImuConfig());
  RigEnvironment env;
  const Decoded d = Decode(RunDevice(device, env, 0.0, 10.0));
  // Samples at 10 ms … 10 s: the packet of the last one is still on the line (7.7 ms at 115,200
  // baud for 51 bytes → 4.4 ms), so 999 complete packets have arrived by t = 10 s.
  ASSERT_EQ(d.data.size(), 999u);
  hil::SequenceTracker tracker;
  for (size_t k = 0; k < d.data.size(); ++k) {
    EXPECT_EQ(d.data[k].sequence, static_cast<uint8_t>(k));
    tracker.Observe(d.data[k].sequence);
    EXPECT_EQ(hil::ParseImuData(d.data[k]).mode, fm::ImuCompensationMode::kRaw);
  }
  EXPECT_EQ(tracker.lost_total(), 0u);
}

TEST(ImuUnitDevice, PacketsCarryThePhysicsOfTheRigEnvironment) {
  // The reference: the same unit (same parameters and noise seed) stepped by the test with the
  // stimulus computed here from the fixture code, gravity and table rate.
  ImuUnitDevice device(ImuConfig());
  sensor_sim::ImuUnit reference(ImuConfig().params, ImuConfig().noise_seed, 25.0);
  RigEnvironment env;
  env.imu_orientation[0] = 22;  // y_B down
  env.table_rate_dps = 60.0;
  env.local_gravity_mps2 = 9.80;
  env.imu_chamber_air_c = 31.0;
  const Decoded d = Decode(RunDevice(device, env, 0.0, 0.5));
  ASSERT_EQ(d.data.size(), 49u);
  sensor_sim::ImuStimulus stimulus;
  stimulus.f_B_g = Eigen::Vector3d(0, -9.80 / 9.80665, 0);
  stimulus.w_B_dps = Eigen::Vector3d(0, -60.0, 0);
  stimulus.air_temp_c = 31.0;
  for (const fm::Frame& f : d.data) {
    const sensor_sim::ImuRawFrame expected = reference.Step(stimulus);
    const fm::ImuDataPayload got = hil::ParseImuData(f);
    for (int ch = 0; ch < 6; ++ch) {
      EXPECT_EQ(got.raw.t1_cnt[ch], expected.accel[static_cast<size_t>(ch)].t1_cnt);
      EXPECT_EQ(got.raw.t2_cnt[ch], expected.accel[static_cast<size_t>(ch)].t2_cnt);
    }
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(got.raw.gyro_cnt[i], expected.gyro_cnt[static_cast<size_t>(i)]);
      EXPECT_EQ(got.raw.temp_cnt[i], expected.temp_cnt[static_cast<size_t>(i)]);
    }
  }
}

TEST(ImuUnitDevice, SameTimelineWhateverTheCallGranularity) {
  ImuUnitDevice fine(ImuConfig()), coarse(ImuConfig());
  RigEnvironment env_fine, env_coarse;
  // 10 ms frames versus 50 ms frames: a packet's bytes are released at their line time either way,
  // so the streams are identical once both have reached the same instant.
  const std::vector<uint8_t> a = RunDevice(fine, env_fine, 0.0, 3.0, 0.01);
  const std::vector<uint8_t> b = RunDevice(coarse, env_coarse, 0.0, 3.0, 0.05);
  EXPECT_EQ(a, b);
}

TEST(ImuUnitDevice, MaintenanceCommandsSetTagModeConstantsCommitAndReset) {
  ImuUnitDevice device(ImuConfig());
  RigEnvironment env;
  hil::UnitProtocolClient client;
  double t = 0.0;

  const hil::IdentifyInfo id = hil::ParseIdentify(Ask(device, env, t, client.Identify()));
  EXPECT_EQ(id.unit_kind, fm::UnitKind::kImu);
  EXPECT_EQ(id.serial_number, 7u);
  EXPECT_FALSE(id.constants_valid);

  // Calibrated mode without committed constants: NAK 0x05 (§6.3).
  EXPECT_EQ(
      Ask(device, env, t, client.SetImuMode(fm::ImuCompensationMode::kFullyCalibrated)).result,
      fm::ResultCode::kNoValidConstants);

  // Every block of a realistic set, then COMMIT.
  const fm::ImuConstants constants = fm::ExportImuConstants(fm::testing::RealisticImu(3)).constants;
  for (uint8_t block = fm::kImuBlockThermalFirst; block <= fm::kImuBlockCg; ++block) {
    int16_t words[fm::kImuMaxBlockWords];
    uint8_t count = 0;
    ASSERT_EQ(fm::ImuConstantsReadBlock(&constants, block, words, fm::kImuMaxBlockWords, &count),
              fm::ConstantsStatus::kOk);
    ASSERT_EQ(Ask(device, env, t, client.WriteBlock(block, {words, count})).result,
              fm::ResultCode::kAck)
        << "block " << int(block);
  }
  const hil::CommitInfo commit = hil::ParseCommit(Ask(device, env, t, client.Commit()));
  EXPECT_EQ(commit.constants_version, 1);

  ASSERT_EQ(Ask(device, env, t, client.SetTag(42)).result, fm::ResultCode::kAck);
  ASSERT_EQ(
      Ask(device, env, t, client.SetImuMode(fm::ImuCompensationMode::kFullyCalibrated)).result,
      fm::ResultCode::kAck);

  // Packets now carry TAG 42 and the compensator's output for their own raw values, computed here
  // with the committed constants.
  const Decoded d = Decode(RunDevice(device, env, t, t + 0.2));
  t += 0.2;
  ASSERT_GE(d.data.size(), 19u);
  for (const fm::Frame& f : d.data) {
    EXPECT_EQ(f.tag, 42);
    const fm::ImuDataPayload got = hil::ParseImuData(f);
    ASSERT_EQ(got.mode, fm::ImuCompensationMode::kFullyCalibrated);
    fm::ImuCompensatedFrame expected{};
    fm::DspEngine engine;
    fm::ImuCompensate(
        &engine, constants, fm::ImuCompensationMode::kFullyCalibrated, got.raw, &expected);
    for (int i = 0; i < fm::kImuOutputValues; ++i)
      EXPECT_EQ(got.compensated.value[i], expected.value[i]);
    EXPECT_EQ(got.compensated.flags, expected.flags);
  }

  // An uncommitted change, then RESET: the committed block returns, mode raw, TAG 0, sequence 0.
  int16_t ca[fm::kImuMaxBlockWords];
  uint8_t ca_count = 0;
  fm::ImuConstantsReadBlock(&constants, fm::kImuBlockCa, ca, fm::kImuMaxBlockWords, &ca_count);
  std::vector<int16_t> changed(ca, ca + ca_count);
  changed[0] = static_cast<int16_t>(changed[0] + 1);
  ASSERT_EQ(Ask(device, env, t, client.WriteBlock(fm::kImuBlockCa, changed)).result,
            fm::ResultCode::kAck);
  const Decoded after_reset = Decode(RunDevice(device, env, t, t + 0.1, 0.01, client.Reset()));
  t += 0.1;
  ASSERT_EQ(after_reset.responses.size(), 1u);
  EXPECT_EQ(after_reset.responses[0].result, fm::ResultCode::kAck);
  ASSERT_FALSE(after_reset.data.empty());
  EXPECT_EQ(after_reset.data.back().tag, 0);
  EXPECT_EQ(hil::ParseImuData(after_reset.data.back()).mode, fm::ImuCompensationMode::kRaw);
  EXPECT_LT(after_reset.data.back().sequence, 10);  // restarted from 0 within the 100 ms
  const hil::BlockReadback back =
      hil::ParseReadBlock(Ask(device, env, t, client.ReadBlock(fm::kImuBlockCa)));
  EXPECT_EQ(back.words, std::vector<int16_t>(ca, ca + ca_count));
}

TEST(ImuUnitDevice, UnpluggedPassesNoBytesEitherWayAndTheSequenceRunsOn) {
  ImuUnitDevice device(ImuConfig());
  RigEnvironment env;
  hil::UnitProtocolClient client;
  RunDevice(device, env, 0.0, 1.0);
  device.SetPhysicalFault("unplugged", true);
  const std::vector<uint8_t> during = RunDevice(device, env, 1.0, 2.0, 0.01, client.SetTag(5));
  EXPECT_TRUE(during.empty());
  device.SetPhysicalFault("unplugged", false);
  const Decoded after = Decode(RunDevice(device, env, 2.0, 2.5));
  ASSERT_FALSE(after.data.empty());
  EXPECT_TRUE(after.responses.empty());
  EXPECT_EQ(after.data.front().tag, 0);  // the SET_TAG never arrived
  // Sample k carries sequence k − 1. Sample 100's packet (t = 1 s) was still on the line when the
  // cable came out, samples 101…199 went into it; sample 200, queued at t = 2 s, leaves the line
  // 4.4 ms after the cable is back: the client's next sequence is 199, a gap of 100.
  EXPECT_EQ(after.data.front().sequence, static_cast<uint8_t>(199));
}

TEST(ImuUnitDevice, ResetFaultIsAPowerCycleThatLosesUncommittedState) {
  ImuUnitDevice device(ImuConfig());
  RigEnvironment env;
  hil::UnitProtocolClient client;
  double t = 0.0;
  ASSERT_EQ(Ask(device, env, t, client.SetTag(9)).result, fm::ResultCode::kAck);
  device.SetPhysicalFault("reset", true);
  EXPECT_TRUE(RunDevice(device, env, t, t + 0.5).size() < 60u);  // at most the packet on the wire
  t += 0.5;
  device.SetPhysicalFault("reset", false);
  const Decoded after = Decode(RunDevice(device, env, t, t + 0.1));
  ASSERT_FALSE(after.data.empty());
  EXPECT_EQ(after.data.front().sequence, 0);
  EXPECT_EQ(after.data.front().tag, 0);
  EXPECT_THROW(device.SetPhysicalFault("on_fire", true), std::invalid_argument);
}

TEST(ImuUnitDevice, AtTooSlowALineCompensatedPacketsAreDroppedAndSeenAsGaps) {
  // docs/unit-protocol.md §1: 57,600 baud cannot carry 89-byte packets at 100 Hz.
  ImuUnitDevice device(ImuConfig(57600));
  RigEnvironment env;
  hil::UnitProtocolClient client;
  double t = 0.0;
  // Raw packets (51 bytes, 8.9 ms) still fit: no loss.
  const Decoded raw = Decode(RunDevice(device, env, 0.0, 2.0));
  hil::SequenceTracker raw_tracker;
  for (const auto& f : raw.data) raw_tracker.Observe(f.sequence);
  EXPECT_EQ(raw_tracker.lost_total(), 0u);
  EXPECT_EQ(device.counters().packets_dropped, 0u);
  t = 2.0;
  // Load constants so a compensated mode is allowed.
  const fm::ImuConstants constants = fm::ExportImuConstants(fm::testing::RealisticImu(5)).constants;
  for (uint8_t block = fm::kImuBlockThermalFirst; block <= fm::kImuBlockCg; ++block) {
    int16_t words[fm::kImuMaxBlockWords];
    uint8_t count = 0;
    fm::ImuConstantsReadBlock(&constants, block, words, fm::kImuMaxBlockWords, &count);
    Ask(device, env, t, client.WriteBlock(block, {words, count}));
  }
  Ask(device, env, t, client.Commit());
  Ask(device, env, t, client.SetImuMode(fm::ImuCompensationMode::kThermal));
  const Decoded comp = Decode(RunDevice(device, env, t, t + 2.0));
  hil::SequenceTracker tracker;
  for (const auto& f : comp.data) tracker.Observe(f.sequence);
  // 5,760 B/s of line for 8,900 B/s of packets: about 35 % of the packets are lost.
  EXPECT_GT(tracker.lost_total(), 50u);
}

TEST(AdsUnitDevice, PacketsCarryTheTestSetPressuresAndTheBenchChamberAir) {
  AdsUnitDeviceConfig config;
  config.serial_number = 3;
  config.params = sensor_sim::AdsUnitParams::Draw("ADS-0003", 77, sensor_sim::ModelProfile::kTruth);
  config.noise_seed = common::Rng::Derive(77, 1);
  AdsUnitDevice device(config);
  sensor_sim::AdsUnit reference(config.params, config.noise_seed, 25.0);
  RigEnvironment env;
  env.ps_pa = 70000.0;
  env.qc_pa = 2500.0;
  env.ads_chamber_air_c = -10.0;
  const Decoded d = Decode(RunDevice(device, env, 0.0, 1.0));
  // 29 bytes take 2.5 ms: by t = 1 s the packets of samples 1…99 have arrived.
  ASSERT_EQ(d.data.size(), 99u);
  sensor_sim::AdsStimulus stimulus{70000.0, 2500.0, -10.0, -10.0};
  for (const fm::Frame& f : d.data) {
    const sensor_sim::AdsRawFrame expected = reference.Step(stimulus);
    const fm::AdsDataPayload got = hil::ParseAdsData(f);
    EXPECT_EQ(got.raw.ps_cnt, expected.ps_cnt);
    EXPECT_EQ(got.raw.pt_cnt, expected.pt_cnt);
    EXPECT_EQ(got.raw.ps_bridge_cnt, expected.ps_temp_cnt);
    EXPECT_EQ(got.raw.pt_bridge_cnt, expected.pt_temp_cnt);
    EXPECT_EQ(got.raw.oat_cnt, expected.oat_cnt);
  }
  hil::UnitProtocolClient client;
  double t = 1.0;
  const hil::IdentifyInfo id = hil::ParseIdentify(Ask(device, env, t, client.Identify()));
  EXPECT_EQ(id.unit_kind, fm::UnitKind::kAds);
  EXPECT_EQ(id.serial_number, 3u);
}

}  // namespace
}  // namespace adahrs::rig_sim
