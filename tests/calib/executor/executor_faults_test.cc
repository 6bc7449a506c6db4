// Faults during a run against the rig process: each must end the run with a message naming the
// instrument (or unit) and the step, leave the rig safe (the rig's own physics: table at rest),
// keep every packet logged so far (the recording reads back, status "aborted").
#include <atomic>
#include <memory>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/executor/run_session.h"
#include "tests/calib/executor/executor_test_util.h"

namespace adahrs::calib {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::RecordingProgress;
using testing::TempDir;

constexpr double kTimeScale = 200.0;

// Runs `steps` (of `unit_kind`) on `rig`; returns the RunError's message ("" if none).
std::string RunExpectingError(const adahrs::testing::RigProcess& rig,
                              const TempDir& dir,
                              const std::string& unit_kind,
                              const nlohmann::json& steps,
                              NewRunOptions options = {}) {
  options.station_file = rig.WriteStation();
  options.sequence_file = testing::WriteSequence(dir.path(), unit_kind, steps);
  options.run_dir = dir.path() / "run";
  RecordingProgress progress;
  std::atomic<bool> stop{false};
  try {
    StartRun(options, progress, stop);
  } catch (const RunError& e) {
    return e.what();
  }
  return "";
}

void ExpectAbortedWithRowsKept(const TempDir& dir, size_t min_rows) {
  const hil::Recording rec = hil::ReadRecording(dir.path() / "run");
  EXPECT_EQ(rec.meta.status.value_or(""), "aborted");
  EXPECT_GE(rec.imu.size() + rec.ads.size(), min_rows);
}

// The table falls silent when the batch is mounted for the gyro step.
TEST(ExecutorFaults, SilentRateTable) {
  adahrs::testing::RigProcess rig(kTimeScale);
  TempDir dir("table_silent");
  NewRunOptions options;
  std::string reply;
  options.wrap_operator =
      testing::DisturbingOperator::Wrapper(rig, 31, "fault rate_table silent on", reply);
  const std::string error = RunExpectingError(rig,
                                              dir,
                                              "imu",
                                              nlohmann::json::parse(R"([
    {"kind": "accel", "orientation": 11, "packets": 100},
    {"kind": "gyro", "orientation": 31, "packets": 100, "rate_min_dps": 50, "rate_max_dps": 50,
     "rate_increment_dps": 10, "table_accel_dps2": 100}])"),
                                              options);
  EXPECT_EQ(reply, "OK rate_table silent on");
  EXPECT_THAT(error,
              AllOf(HasSubstr("step 1 (gyro"), HasSubstr("rate_table"), HasSubstr("no reply")));
  EXPECT_NEAR(testing::RigTableRateDps(rig), 0.0, 1e-9);
  // Step 0's 100 packets per unit plus the gyro interlock's rest average: all kept.
  ExpectAbortedWithRowsKept(dir, 4 * 200);
}

TEST(ExecutorFaults, ChamberRefusesASetPointBeyondItsLimit) {
  auto config = nlohmann::json::parse(adahrs::testing::RigProcess(kTimeScale).config().dump());
  config["instruments"]["watlow_f4"]["controller"]["set_point_high_limit_c"] = 40.0;
  adahrs::testing::RigProcess rig(kTimeScale, config);
  TempDir dir("f4_limit");
  const std::string error = RunExpectingError(rig, dir, "imu", nlohmann::json::parse(R"([
    {"kind": "accel", "orientation": 31, "packets": 100},
    {"kind": "target_temperature", "target_c": 60.0, "band_c": 1.0, "soak_s": 10.0}])"));
  EXPECT_THAT(error,
              AllOf(HasSubstr("step 1 (target_temperature"),
                    HasSubstr("imu_chamber"),
                    HasSubstr("exception")));
  EXPECT_NEAR(testing::RigTableRateDps(rig), 0.0, 1e-9);
  ExpectAbortedWithRowsKept(dir, 4 * 100);
}

TEST(ExecutorFaults, AirDataTestSetNeverStable) {
  adahrs::testing::RigProcess rig(kTimeScale);
  TempDir dir("adts_unstable");
  ASSERT_EQ(rig.Control("fault adts never_stable on"), "OK adts never_stable on");
  const std::string error = RunExpectingError(rig, dir, "ads", nlohmann::json::parse(R"([
    {"kind": "altitude", "alt_ft": 2000.0, "rate_ft_per_min": 6000.0},
    {"kind": "log", "packets": 100}])"));
  EXPECT_THAT(error,
              AllOf(HasSubstr("step 0 (altitude"), HasSubstr("adts"), HasSubstr("not stable")));
  const hil::Recording rec = hil::ReadRecording(dir.path() / "run");
  EXPECT_EQ(rec.meta.status.value_or(""), "aborted");
  EXPECT_GT(rec.ads.size(), 1000u);  // over 100 s of waiting at 100 Hz, all logged
}

// The unit's cable comes out right after the fixture moved to 32 (a disturbance the test adds
// to the operator): the interlock's average never completes for imu3.
TEST(ExecutorFaults, UnitUnpluggedMidStep) {
  adahrs::testing::RigProcess rig(kTimeScale);
  TempDir dir("unplugged");
  NewRunOptions options;
  std::string reply;
  options.wrap_operator =
      testing::DisturbingOperator::Wrapper(rig, 32, "fault imu3 unplugged on", reply);
  const std::string error = RunExpectingError(rig,
                                              dir,
                                              "imu",
                                              nlohmann::json::parse(R"([
    {"kind": "accel", "orientation": 11, "packets": 200},
    {"kind": "accel", "orientation": 32, "packets": 200}])"),
                                              options);
  EXPECT_EQ(reply, "OK imu3 unplugged on");
  EXPECT_THAT(error, AllOf(HasSubstr("step 1 (accel"), HasSubstr("imu3 (IMU-0003)")));
  EXPECT_NEAR(testing::RigTableRateDps(rig), 0.0, 1e-9);
  const hil::Recording rec = hil::ReadRecording(dir.path() / "run");
  EXPECT_EQ(rec.meta.status.value_or(""), "aborted");
  EXPECT_EQ(testing::TaggedImuRows(rec).at({"IMU-0003", 1}).size(), 200u);  // step 0 kept
}

}  // namespace
}  // namespace adahrs::calib
