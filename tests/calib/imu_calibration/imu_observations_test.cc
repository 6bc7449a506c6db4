// Observations keep when their rows were taken (for the gyro bias-wander covariance): the run,
// and the time windows of the rows, a thermal band revisited by a later ramp having two windows;
// thermal bands of different runs stay apart even when their clocks overlap.
#include "calib/imu_calibration/imu_observations.h"

#include <gtest/gtest.h>

namespace adahrs::calib {
namespace {

ImuSample Row(double t_s, uint16_t temp_cnt, int run) {
  ImuSample s;
  for (int ch = 0; ch < 6; ++ch) {
    s.raw.t1_cnt[ch] = 5000;
    s.raw.t2_cnt[ch] = 10000;
  }
  for (int g = 0; g < 3; ++g) {
    s.raw.gyro_cnt[g] = 4194304;
    s.raw.temp_cnt[g] = temp_cnt;
  }
  s.t_s = t_s;
  s.run = run;
  return s;
}

TEST(ImuObservations, KeepTheRunAndTheTimeWindowsOfTheirRows) {
  ImuUnitData unit;
  unit.serial = "IMU-T";
  unit.thermal_orientation = 31;
  // Run 0: up through band 300 (t 0...0.99 s), away (band 301), and up through band 300 again
  // 100 s later. Run 1, same clock: band 300 up for 0.5 s.
  auto add = [&](double t0_s, int rows, uint16_t temp_cnt, int run) {
    for (int i = 0; i < rows; ++i) {
      unit.thermal.push_back(Row(t0_s + 0.01 * i, temp_cnt, run));
      unit.thermal_segment.push_back(ThermalSegment::kUpRamp);
    }
  };
  add(0.0, 100, 33000, 0);
  add(1.0, 50, 33120, 0);
  add(100.0, 30, 33010, 0);
  add(0.0, 50, 33005, 1);
  ImuAcquisition acq{"run-b", 3, "accel", 11, 0.0, {}};
  for (int i = 0; i < 20; ++i) acq.samples.push_back(Row(5.0 + 0.01 * i, 32800, 1));
  unit.accel.push_back(acq);

  const std::vector<ImuObservation> obs = ImuObservations(unit, 9.80665, 110.0);
  ASSERT_EQ(obs.size(), 4u);
  const ImuObservation& accel = obs[0];
  EXPECT_FALSE(accel.thermal);
  EXPECT_EQ(accel.run, 1);
  ASSERT_EQ(accel.windows.size(), 1u);
  EXPECT_DOUBLE_EQ(accel.windows[0].first_s, 5.0);
  EXPECT_NEAR(accel.windows[0].last_s, 5.19, 1e-12);
  EXPECT_EQ(accel.windows[0].rows, 20);

  // Thermal bands in (run, band, segment) order: run 0 band 300, run 0 band 301, run 1 band 300.
  const ImuObservation& revisited = obs[1];
  EXPECT_EQ(revisited.run, 0);
  EXPECT_EQ(revisited.count, 130);
  ASSERT_EQ(revisited.windows.size(), 2u);
  EXPECT_DOUBLE_EQ(revisited.windows[0].first_s, 0.0);
  EXPECT_EQ(revisited.windows[0].rows, 100);
  EXPECT_DOUBLE_EQ(revisited.windows[1].first_s, 100.0);
  EXPECT_EQ(revisited.windows[1].rows, 30);
  EXPECT_EQ(obs[2].run, 0);
  EXPECT_EQ(obs[2].count, 50);
  EXPECT_EQ(obs[3].run, 1);
  EXPECT_EQ(obs[3].count, 50);
  ASSERT_EQ(obs[3].windows.size(), 1u);
  EXPECT_NE(obs[1].source, obs[3].source);
}

}  // namespace
}  // namespace adahrs::calib
