// The executor against the virtual rig as a separate process (the production code path: station
// file, serial ports, drivers). Expected values come from the sequence (N, orientations, rates)
// and the rig's own report of its physics (control port `env`), never from the executor.
#include <atomic>
#include <cmath>
#include <memory>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/executor/run_session.h"
#include "tests/calib/executor_test_util.h"

namespace adahrs::calib {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::RecordingProgress;
using testing::TempDir;

// 200x: the sequence's ~2 simulated minutes take under a second of wall time, well inside the
// rig's loss-free range (docs/performance.md), on 2 shared cores.
constexpr double kTimeScale = 200.0;

const nlohmann::json kShortImuSteps = nlohmann::json::parse(R"([
  {"kind": "target_temperature", "target_c": 25.0, "band_c": 1.0, "soak_s": 10.0},
  {"kind": "accel", "orientation": 11, "packets": 200},
  {"kind": "accel", "orientation": 32, "packets": 200},
  {"kind": "gyro", "orientation": 31, "packets": 100, "rate_min_dps": -100, "rate_max_dps": 100,
   "rate_increment_dps": 100, "table_accel_dps2": 100}
])");

TEST(ExecutorRig, ShortImuSequenceRecordsExactlyTheAcquisitionsOfFourUnits) {
  adahrs::testing::RigProcess rig(kTimeScale);
  TempDir dir("short");
  NewRunOptions options;
  options.station_file = rig.WriteStation();
  options.sequence_file = testing::WriteSequence(dir.path(), "imu", kShortImuSteps);
  options.run_dir = dir.path() / "run";
  RecordingProgress progress;
  std::atomic<bool> stop{false};
  const RunSummary summary = StartRun(options, progress, stop);
  EXPECT_EQ(summary.status, "complete");
  EXPECT_EQ(summary.lost, 0u);

  const hil::Recording rec = hil::ReadRecording(options.run_dir);
  EXPECT_EQ(rec.meta["status"], "complete");
  EXPECT_EQ(rec.meta["units"].size(), 4u);
  EXPECT_TRUE(rec.rejected_intervals.empty());
  EXPECT_EQ(rec.imu.size(), summary.rows);
  for (const auto& [unit, gaps] : testing::SequenceGaps(rec)) EXPECT_EQ(gaps, 0) << unit;

  const auto tagged = testing::TaggedImuRows(rec);
  for (int u = 1; u <= 4; ++u) {
    const std::string serial = "IMU-000" + std::to_string(u);
    EXPECT_FALSE(tagged.contains({serial, 1})) << "target_temperature acquires nothing";
    const auto& accel11 = tagged.at({serial, 2});
    const auto& accel32 = tagged.at({serial, 3});
    const auto& gyro = tagged.at({serial, 4});
    EXPECT_EQ(accel11.size(), 200u) << serial;
    EXPECT_EQ(accel32.size(), 200u) << serial;
    ASSERT_EQ(gyro.size(), 300u) << serial;  // 3 rates x 100
    for (const auto& r : accel11) EXPECT_EQ(r.orientation, 11);
    for (const auto& r : accel32) EXPECT_EQ(r.orientation, 32);
    // Each rate's acquisition: the table's reported rate within 0.01 deg/s of the command.
    std::map<long, int> per_rate;
    for (const auto& r : gyro) {
      EXPECT_EQ(r.orientation, 31);
      const long command = std::lround(r.table_rate_dps / 100.0) * 100;
      EXPECT_NEAR(r.table_rate_dps, static_cast<double>(command), 0.01);
      ++per_rate[command];
    }
    EXPECT_EQ(per_rate, (std::map<long, int>{{-100, 100}, {0, 100}, {100, 100}})) << serial;
  }
  EXPECT_NEAR(testing::RigTableRateDps(rig), 0.0, 1e-9);
}

TEST(ExecutorRig, WrongOrientationStopsTheRunAndTagsNothing) {
  adahrs::testing::RigProcess rig(kTimeScale);
  TempDir dir("interlock");
  NewRunOptions options;
  options.station_file = rig.WriteStation();
  options.sequence_file = testing::WriteSequence(dir.path(), "imu", kShortImuSteps);
  options.run_dir = dir.path() / "run";
  // The disturbance: after every mount in 32, imu2 is turned back to 31 (the wrong way up).
  std::string reply;
  options.wrap_operator = testing::DisturbingOperator::Wrapper(rig, 32, "orientation imu2 31", reply);
  RecordingProgress progress;
  std::atomic<bool> stop{false};
  try {
    StartRun(options, progress, stop);
    FAIL() << "the run should have stopped";
  } catch (const RunError& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("step 2 (accel"), HasSubstr("gravity interlock failed"),
                                HasSubstr("imu2 (IMU-0002)")));
    EXPECT_THAT(e.what(), ::testing::Not(HasSubstr("imu1")));
  }
  EXPECT_EQ(reply, "OK imu2 31");
  const hil::Recording rec = hil::ReadRecording(options.run_dir);
  EXPECT_EQ(rec.meta["status"], "aborted");
  ASSERT_EQ(rec.rejected_intervals.size(), 3u);  // every attempt
  for (const auto& r : rec.rejected_intervals) EXPECT_EQ(r.step, 2);
  for (const auto& r : rec.imu) EXPECT_NE(r.tag, 3) << "no row tagged for step 2";
  EXPECT_EQ(testing::TaggedImuRows(rec).at({"IMU-0002", 2}).size(), 200u);  // step 1 kept
  EXPECT_NEAR(testing::RigTableRateDps(rig), 0.0, 1e-9);
}

}  // namespace
}  // namespace adahrs::calib
