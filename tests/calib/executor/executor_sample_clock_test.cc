// The units' sample clock at the demo's top speed: the executor against a lockstep rig at 900x
// (docs/demo.md) as a separate process, beside a CPU-bound process, over a short IMU and a short
// ADS calibration run, and the IMU run again in lockstep as fast as the machine allows. Truth: the
// rig's own packet log (packets/<role>.txt, the sample index of every packet each unit sent:
// rig_sim/unit_device.h), never the pipeline's count. For every unit and every row: frame - first
// frame equals the rig's sample index - the first row's, exactly, and |t_sample_s - t_s| stays
// within the lockstep line's buffering: the rig runs at most 100 + 10 frames past what a reader has
// read and 10 frames in a tick (docs/rig.md "Port counts file"), 1.1 s, and a packet leaves its
// unit's line within a frame; 1.2 s, on the run's time base, which starts on a whole counter turn
// of the rig's frames (docs/rig.md "Clock file"). The reader finds no sample time defect, and
// meta.json states that bound for every unit (the rig's counts were used).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include <gtest/gtest.h>

#include "calib/executor/run_session.h"
#include "hil/recording/frame_count.h"
#include "tests/calib/executor/executor_test_util.h"
#include "tests/support/busy_loop.h"

namespace adahrs::calib {
namespace {

using testing::RecordingProgress;
using testing::TempDir;

constexpr double kTopSpeed = 900.0;  // the demo's default (apps/demo_command.cc)
constexpr double kLineBuffering_s = 1.2;
// A packet is read at most a tick's frames before the rig publishes them: 10 (docs/rig.md).
constexpr double kAheadOfTheClock_s = 0.1;
constexpr double kHighestScale = 100000.0;  // the rig's largest time_scale (docs/rig.md)

struct RigPacket {
  int64_t sample = 0;  // the unit's sample index since the rig started
  unsigned seq = 0;
  std::string fingerprint;  // the packet's first 8 payload bytes, hex
};

std::vector<RigPacket> ReadPacketLog(const std::filesystem::path& path) {
  std::vector<RigPacket> log;
  std::ifstream in(path);
  RigPacket p;
  while (in >> p.sample >> p.seq >> p.fingerprint) log.push_back(p);
  return log;
}

std::string Hex(std::initializer_list<uint32_t> words, int bytes_each) {
  std::string out;
  char byte[3];
  for (uint32_t w : words) {
    for (int i = 0; i < bytes_each; ++i) {
      std::snprintf(byte, sizeof byte, "%02x", (w >> (8 * i)) & 0xFFu);
      out += byte;
    }
  }
  return out;
}

// The payload's first 8 bytes as the unit encoded them (docs/unit-protocol.md §4, §5).
std::string Fingerprint(const hil::ImuRecordRow& r) {
  return Hex({r.accel_ticks[0], r.accel_ticks[1], r.accel_ticks[2], r.accel_ticks[3]}, 2);
}
std::string Fingerprint(const hil::AdsRecordRow& r) {
  return Hex({static_cast<uint32_t>(r.ps_cnt), static_cast<uint32_t>(r.pt_cnt)}, 4);
}

template <typename Row>
bool Matches(const RigPacket& logged, const Row& r) {
  return logged.seq == r.seq && logged.fingerprint == Fingerprint(r);
}

// Where the first rows sit in the log: the first position from which the first kAnchorRows rows
// match consecutively. A counter value and 8 payload bytes alone repeat: a unit at rest in its
// soak sends the same accelerometer ticks turn after turn of its counter.
template <typename Row>
size_t FirstRowInLog(const std::vector<const Row*>& rows, const std::vector<RigPacket>& log) {
  constexpr size_t kAnchorRows = 50;
  const size_t n = std::min(kAnchorRows, rows.size());
  for (size_t j = 0; j + n <= log.size(); ++j) {
    size_t m = 0;
    while (m < n && Matches(log[j + m], *rows[m])) ++m;
    if (m == n) return j;
  }
  return log.size();
}

// Each row of `unit` against the rig's log of its packets, in order (a packet the pipeline lost
// is skipped in the log, and counted by both).
template <typename Row>
void ExpectTheRigsCount(const std::vector<Row>& all_rows,
                        const std::string& unit,
                        const std::vector<RigPacket>& log) {
  SCOPED_TRACE(unit);
  std::vector<const Row*> unit_rows;
  for (const Row& r : all_rows) {
    if (r.unit == unit) unit_rows.push_back(&r);
  }
  size_t j = FirstRowInLog(unit_rows, log);
  int64_t first_frame = 0, first_sample = 0, rows = 0;
  double lo_s = 1e9, hi_s = -1e9;
  for (const Row* row : unit_rows) {
    const Row& r = *row;
    while (j < log.size() && !Matches(log[j], r)) ++j;
    ASSERT_LT(j, log.size()) << "row " << rows << " (seq " << r.seq << ", t_s " << r.t_s
                             << ") is no packet the rig logged after the previous row's";
    if (rows++ == 0) {
      first_frame = r.frame;
      first_sample = log[j].sample;
    }
    ASSERT_EQ(r.frame - first_frame, log[j].sample - first_sample)
        << "row " << rows - 1 << " at t_s " << r.t_s;
    const double offset_s = hil::SampleTimeS(r.frame) - r.t_s;
    lo_s = std::min(lo_s, offset_s);
    hi_s = std::max(hi_s, offset_s);
    ++j;
  }
  EXPECT_GT(rows, 1000);
  // t_s to 0.1 ms in the file.
  EXPECT_LE(std::max(std::abs(lo_s), std::abs(hi_s)), kLineBuffering_s + 1e-4);
  EXPECT_LE(hi_s, kAheadOfTheClock_s + 1e-4);
  std::printf("%s: %lld rows, t_sample_s - t_s from %+.3f to %+.3f s\n",
              unit.c_str(),
              static_cast<long long>(rows),
              lo_s,
              hi_s);
}

// Runs `steps` on the rig into `dir`/run; checks the run and returns its recording.
hil::Recording RunAndCheck(const adahrs::testing::RigProcess& rig,
                           const TempDir& dir,
                           const std::string& kind,
                           const nlohmann::json& steps) {
  NewRunOptions options;
  options.station_file = rig.WriteStation("station-" + kind + ".json");
  options.sequence_file = testing::WriteSequence(dir.path(), kind, steps);
  options.run_dir = dir.path() / ("run-" + kind);
  RecordingProgress progress;
  std::atomic<bool> stop{false};
  const RunSummary summary = StartRun(options, progress, stop);
  EXPECT_EQ(summary.status, "complete");
  EXPECT_EQ(summary.lost, 0u);
  hil::Recording rec = hil::ReadRecording(options.run_dir);
  for (const hil::SampleTimeDefect& d : rec.sample_time_defects) ADD_FAILURE() << d.Describe();
  for (const hil::RecordingUnit& unit : rec.meta.units) {
    // The lockstep rig's counts were used (the bound the executor states for them).
    EXPECT_EQ(unit.line_buffering_s, std::optional<double>(kLineBuffering_s)) << unit.serial;
  }
  return rec;
}

void RunBothBenches(double time_scale, bool ads_too) {
  nlohmann::json config = adahrs::testing::RigProcess::BuiltInConfig();
  config["packet_log"] = true;
  adahrs::testing::RigProcess rig(time_scale, config, /*lockstep=*/true);
  TempDir dir("sample_clock");
  const adahrs::testing::BusyLoop busy;
  const hil::Recording imu = RunAndCheck(rig, dir, "imu", nlohmann::json::parse(R"([
    {"kind": "target_temperature", "target_c": 25.0, "band_c": 1.0, "soak_s": 120.0},
    {"kind": "accel", "orientation": 11, "packets": 200},
    {"kind": "accel", "orientation": 32, "packets": 200},
    {"kind": "gyro", "orientation": 31, "packets": 100, "rate_min_dps": -100, "rate_max_dps": 100,
     "rate_increment_dps": 100, "table_accel_dps2": 100}])"));
  const hil::Recording ads =
      !ads_too ? hil::Recording{} : RunAndCheck(rig, dir, "ads", nlohmann::json::parse(R"([
    {"kind": "target_temperature", "target_c": 25.0, "band_c": 1.0, "soak_s": 120.0},
    {"kind": "altitude", "alt_ft": 0.0, "rate_ft_per_min": 3000.0},
    {"kind": "log", "packets": 200},
    {"kind": "altitude", "alt_ft": 5000.0, "rate_ft_per_min": 3000.0},
    {"kind": "airspeed", "cas_kt": 100.0, "rate_kt_per_min": 200.0},
    {"kind": "log", "packets": 200}])"));
  rig.Terminate();  // flushes the packet logs
  for (const hil::RecordingUnit& unit : imu.meta.units) {
    ExpectTheRigsCount(
        imu.imu, unit.serial, ReadPacketLog(rig.dir() / "packets" / (unit.role + ".txt")));
  }
  for (const hil::RecordingUnit& unit : ads.meta.units) {
    ExpectTheRigsCount(
        ads.ads, unit.serial, ReadPacketLog(rig.dir() / "packets" / (unit.role + ".txt")));
  }
}

TEST(ExecutorSampleClock, AtTheDemosTopSpeedBesideABusyLoopEveryFrameIsTheRigsOwn) {
  RunBothBenches(kTopSpeed, /*ads_too=*/true);
}

// Lockstep as fast as the machine allows (the rig's highest time scale): the count is exact at
// any speed, since the rig holds on packets, not on time.
TEST(ExecutorSampleClock, AsFastAsTheMachineAllowsEveryFrameIsTheRigsOwn) {
  RunBothBenches(kHighestScale, /*ads_too=*/false);
}

}  // namespace
}  // namespace adahrs::calib
