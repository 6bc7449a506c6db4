// The study's in-process run (ImuRunSimulator rows handed to ImuRunCollector) against the same
// run written as a recording by the test maker and read back by LoadImuRuns: the collected data
// and the fitted constants must be the same, so a study judges what a recording would give.
// And a frameless soak leaves the dies where the same soak in frames leaves them.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "adahrs_build_paths.h"
#include "calib/imu_calibration/imu_run_data.h"
#include "calib/imu_calibration/imu_strategy.h"
#include "calib/sequence/sequence_json.h"
#include "common/gravity.h"
#include "firmware_model/calibration_constants.h"
#include "proving/studies/imu_run_simulator.h"
#include "tests/support/imu_recording_maker.h"

namespace adahrs::proving {
namespace {

const double kG_mps2 = common::NormalGravityMps2(34.7, 190.0);

calib::Sequence ShortSequence() {
  const std::string file =
      std::string(ADAHRS_SOURCE_DIR) + "/tests/data/studies/short_imu_calibration.json";
  return calib::SequenceFromJson(common::ParamReader::LoadFile(file), file);
}

TEST(ImuRunSimulator, InMemoryRunCollectsAndFitsAsItsRecordingDoes) {
  const sensor_sim::ImuUnitParams params =
      sensor_sim::ImuUnitParams::Draw("IMU-0042", 42, sensor_sim::ModelProfile::kTruth);
  const calib::Sequence sequence = ShortSequence();
  calib::testing::MakerOptions maker_options;
  maker_options.thermal_speedup = 1.0;

  const auto run = std::filesystem::temp_directory_path() / "adahrs_imu_run_simulator_test";
  calib::testing::ImuRecordingMaker(std::vector{params}, kG_mps2, 9, maker_options)
      .Run(sequence, run);
  const calib::ImuRunData from_disk = calib::LoadImuRuns({run});
  std::filesystem::remove_all(run);

  calib::ImuRunData in_memory;
  calib::ImuRunCollector collector(
      "memory", "", sequence, kG_mps2, {params.serial}, {}, &in_memory);
  ImuRunSimulator simulator({params},
                            kG_mps2,
                            9,
                            {maker_options.settle_frames,
                             maker_options.soak_frames,
                             1.0,
                             maker_options.table_rate_error_dps,
                             maker_options.initial_air_temp_c});
  simulator.Run(sequence, [&](const hil::ImuRecordRow& row) { collector.Take(row, 0); });
  collector.Finish();

  const calib::ImuUnitData& a = from_disk.units.at(params.serial);
  const calib::ImuUnitData& b = in_memory.units.at(params.serial);
  ASSERT_EQ(a.thermal.size(), b.thermal.size());
  ASSERT_EQ(a.accel.size(), 7u);  // the orientation-31 reference and the six positions
  ASSERT_EQ(b.accel.size(), a.accel.size());
  ASSERT_EQ(b.gyro.size(), a.gyro.size());
  ASSERT_EQ(b.cross_axis.size(), a.cross_axis.size());
  EXPECT_EQ(b.thermal_segment, a.thermal_segment);
  for (size_t i = 0; i < a.thermal.size(); i += 997) {
    EXPECT_EQ(b.thermal[i].raw.gyro_cnt[2], a.thermal[i].raw.gyro_cnt[2]) << i;
    EXPECT_EQ(b.thermal[i].raw.t1_cnt[0], a.thermal[i].raw.t1_cnt[0]) << i;
    EXPECT_EQ(b.thermal[i].chamber_c, a.thermal[i].chamber_c) << i;
  }
  for (const calib::ImuStrategy& strategy :
       {calib::ImuStrategy::Reference(), calib::ImuStrategy::JointFormat2()}) {
    SCOPED_TRACE(strategy.name);
    const calib::ConstantsFile fa = calib::FitImuUnit(a, from_disk, strategy, "test");
    const calib::ConstantsFile fb = calib::FitImuUnit(b, in_memory, strategy, "test");
    EXPECT_EQ(firmware_model::ToJson(*fb.imu), firmware_model::ToJson(*fa.imu));
  }
}

TEST(ImuRunSimulator, AFramelessSoakLeavesTheDiesWhereFramesWould) {
  const sensor_sim::ImuUnitParams params =
      sensor_sim::ImuUnitParams::Draw("IMU-0043", 43, sensor_sim::ModelProfile::kTruth);
  sensor_sim::ImuUnit framed(params, 1, 25.0), frameless(params, 1, 25.0);
  sensor_sim::ImuStimulus cold;
  cold.air_temp_c = -40.0;
  for (int i = 0; i < 90000; ++i) framed.Step(cold);  // 15 min of frames
  frameless.SoakWithoutFrames(-40.0, 900.0);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(frameless.die_temperatures().accel_chip_c[k],
                framed.die_temperatures().accel_chip_c[k],
                1e-9);
    EXPECT_NEAR(frameless.die_temperatures().gyro_c[k], framed.die_temperatures().gyro_c[k], 1e-9);
  }
  EXPECT_LT(frameless.die_temperatures().gyro_c[0], 0.0);  // well on its way to -40 degC
}

}  // namespace
}  // namespace adahrs::proving
