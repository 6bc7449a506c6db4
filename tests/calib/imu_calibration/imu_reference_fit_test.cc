// "Reproduces the reference" from recordings: four simulated IM3 units with the reference hardware
// magnitudes (ModelProfile::kNominal) are taken through the shipped thermal calibration (-40...85
// degC, time-compressed) and sensor calibration sequences by the recording maker, written as the
// executor writes them, read back by LoadImuRuns and fitted by the
// reference strategy. Expected magnitudes come from the datasheets and the reference tables.
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/constants/constants_file.h"
#include "calib/constants/imu_fit_diagnostics.h"
#include "calib/imu_calibration/imu_reference_fit.h"
#include "calib/imu_calibration/imu_run_data.h"
#include "calib/imu_calibration/imu_strategy.h"
#include "common/gravity.h"
#include "tests/support/imu_recording_maker.h"

namespace adahrs::calib {
namespace {

using sensor_sim::ImuUnitParams;

const double kGLocal_mps2 = common::NormalGravityMps2(32.6, 200.0);  // Auburn AL

struct Runs {
  std::filesystem::path thermal, sensor;
  std::vector<ImuUnitParams> params;
};

const Runs& SharedRuns() {
  static const Runs runs = [] {
    Runs r;
    // One directory per process: ctest runs this file's tests side by side.
    const auto base = std::filesystem::temp_directory_path() /
                      ("adahrs_imu_reference_fit_" + std::to_string(::getpid()));
    r.thermal = base / "thermal";
    r.sensor = base / "sensor";
    for (int i = 0; i < 4; ++i) {
      r.params.push_back(ImuUnitParams::Draw(
          "IMU-000" + std::to_string(i + 1), 2007 + i, sensor_sim::ModelProfile::kNominal));
    }
    testing::ImuRecordingMaker maker(r.params, kGLocal_mps2, 77);
    maker.Run(testing::ShippedSequence("imu_thermal_calibration_full", 500), r.thermal);
    maker.Run(testing::ShippedSequence("imu_sensor_calibration", 500), r.sensor);
    return r;
  }();
  return runs;
}

TEST(ImuReferenceFit, ConstantsHaveTheReferenceMagnitudes) {
  const Runs& runs = SharedRuns();
  const ImuRunData data = LoadImuRuns({runs.thermal, runs.sensor});
  ASSERT_EQ(data.units.size(), 4u);
  EXPECT_EQ(data.local_gravity_mps2, kGLocal_mps2);
  for (const auto& [serial, unit] : data.units) {
    SCOPED_TRACE(serial);
    // Six orientations of the sensor run plus the thermal run's orientation 31; 7 rates x 3 axes.
    EXPECT_EQ(unit.accel.size(), 7u);
    EXPECT_EQ(unit.gyro.size(), 21u);
    EXPECT_EQ(unit.cross_axis.size(), 6u);
    const ImuFitResult fit = FitImuReference(unit, data.local_gravity_mps2);
    // 1/S: Table 16 |1/S| 25.08...25.93 g per duty, signs - - + + + -; ADXL210E 4 %/g +-20 % (R)
    // allows 20.8...31.3.
    constexpr std::array<double, 6> kSign = {-1, -1, 1, 1, 1, -1};
    for (int ch = 0; ch < 6; ++ch) {
      const double inv = 1.0 / fit.constants.accel[ch].scale_duty_per_g;
      EXPECT_EQ(std::copysign(1.0, inv), kSign[ch]) << ch;
      EXPECT_GT(std::abs(inv), 20.8) << ch;
      EXPECT_LT(std::abs(inv), 31.3) << ch;
    }
    // l1 = 1 / (16 * 2^19 / 5 V * S), S = 12.5 +-1.25 mV/(deg/s): 4.34e-5...5.30e-5 (Table 18:
    // 4.68...4.84e-5); l3 ~ 1e-20.
    for (int g = 0; g < 3; ++g) {
      EXPECT_GT(fit.constants.gyro[g].l[1], 4.34e-5) << g;
      EXPECT_LT(fit.constants.gyro[g].l[1], 5.30e-5) << g;
      EXPECT_LT(std::abs(fit.constants.gyro[g].l[3]), 1e-18) << g;
      EXPECT_GT(fit.standard_errors.gyro[g].l[1], 0.0);
    }
    // Off-diagonals of order 0.01 (misalignments within +-1 deg per component, im3_geometry.h).
    double largest_off = 0.0;
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) {
        const double ca = fit.constants.ca_mps2_per_g[r][k] / common::kStandardGravity_mps2;
        const double cg = fit.constants.cg[r][k];
        if (r == k) {
          EXPECT_NEAR(ca, 1.0, 0.01);
          EXPECT_NEAR(cg, 1.0, 0.01);
        } else {
          EXPECT_LT(std::abs(ca), 0.05);
          EXPECT_LT(std::abs(cg), 0.05);
          largest_off = std::max({largest_off, std::abs(ca), std::abs(cg)});
        }
      }
    }
    EXPECT_GT(largest_off, 0.002);
    // Both ramp directions present and fitted separately.
    ASSERT_TRUE(fit.diagnostics.reference.has_value());
    EXPECT_TRUE(fit.diagnostics.reference->thermal.at("gx").up_ramp_k.has_value());
    EXPECT_TRUE(fit.diagnostics.reference->thermal.at("gx").down_ramp_k.has_value());
  }
}

// Both strategies' diagnostics survive constants.json: written, read back and parsed, they hold the
// recording's local gravity, every channel and no excluded row (the recording has none); the joint
// strategy's bound is a covariance of its named firmware numbers (square, symmetric, non-negative
// diagonal); and the parsed struct writes back exactly the section read.
TEST(ImuReferenceFit, DiagnosticsReadBackFromTheConstantsFiles) {
  const Runs& runs = SharedRuns();
  const auto dir = std::filesystem::temp_directory_path() /
                   ("adahrs_imu_diagnostics_read_back_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (const ImuStrategy& strategy : {ImuStrategy::Reference(), ImuStrategy::JointFormat2()}) {
    for (const ConstantsFile& f : FitImuRuns({runs.thermal, runs.sensor}, strategy, "test")) {
      SCOPED_TRACE(strategy.name + " " + f.serial);
      const auto path = dir / (f.serial + ".json");
      WriteConstantsFile(path, f);
      const ConstantsFile read = ReadConstantsFile(path);
      ASSERT_TRUE(read.imu_diagnostics.has_value());
      const ImuFitDiagnostics& d = *read.imu_diagnostics;
      EXPECT_EQ(d.local_gravity_mps2.value_or(0.0), kGLocal_mps2);
      EXPECT_EQ(d.excluded_rows.value_or(-1), 0);
      // What was read writes back as the fit wrote it (numbers, keys and nulls).
      EXPECT_EQ(ToJson(read)["diagnostics"], ToJson(f)["diagnostics"]);
      if (strategy.name == "reference") {
        ASSERT_TRUE(d.reference.has_value());
        EXPECT_EQ(d.reference->thermal.size(), 9u);
        EXPECT_EQ(d.reference->accel.size(), 6u);
        EXPECT_EQ(d.reference->gyro.size(), 3u);
        continue;
      }
      ASSERT_TRUE(d.joint.has_value());
      EXPECT_EQ(d.joint->channels.size(), 9u);
      const auto& crb = d.joint->crb_covariance;
      ASSERT_EQ(crb.size(), d.joint->crb_parameters.size());
      for (size_t r = 0; r < crb.size(); ++r) {
        ASSERT_EQ(crb[r].size(), crb.size());
        EXPECT_GE(crb[r][r], 0.0) << d.joint->crb_parameters[r];
        for (size_t k = 0; k < r; ++k) {
          EXPECT_NEAR(crb[r][k], crb[k][r], 1e-9 * std::sqrt(crb[r][r] * crb[k][k]))
              << r << "," << k;
        }
      }
    }
  }
  std::filesystem::remove_all(dir);
}

// The staged process fits the reference method's steps one at a time, each on the constants file
// of the one before: on the same rows it gives the one-shot fit's constants and standard errors to
// the last bit (the base file's doubles round-trip through JSON), and each file says which stages
// it holds, the later ones at their defaults.
TEST(ImuReferenceFit, StagedFitsReproduceTheOneShotFitStageByStage) {
  const Runs& runs = SharedRuns();
  const auto dir = std::filesystem::temp_directory_path() /
                   ("adahrs_imu_staged_fit_" + std::to_string(::getpid()));
  const std::vector<std::filesystem::path> both = {runs.thermal, runs.sensor};
  std::filesystem::path base;
  std::vector<ConstantsFile> staged;
  for (ImuStage stage : kImuStages) {
    const auto out = dir / std::string(ImuStageName(stage));
    std::filesystem::create_directories(out);
    staged = FitImuRuns(both, ImuStrategy::Reference(), "test", ImuStageRequest{stage, base});
    for (const ConstantsFile& f : staged) {
      EXPECT_EQ(f.stages, StagesThrough(stage));
      WriteConstantsFile(out / (f.serial + ".json"), f);
    }
    if (stage == ImuStage::kThermal) {  // the later stages hold their defaults
      const firmware_model::ImuCalibrationConstants& c = *staged.front().imu;
      EXPECT_EQ(c.accel[0].scale_duty_per_g, firmware_model::AccelScaleFit{}.scale_duty_per_g);
      EXPECT_EQ(c.gyro[0].l[1], 0.0);
      EXPECT_EQ(c.cg[0][0], 1.0);
      EXPECT_EQ(c.cg[0][1], 0.0);
    }
    base = out;
  }
  const std::vector<ConstantsFile> one_shot = FitImuRuns(both, ImuStrategy::Reference(), "test");
  ASSERT_EQ(staged.size(), one_shot.size());
  for (size_t i = 0; i < staged.size(); ++i) {
    SCOPED_TRACE(staged[i].serial);
    const ConstantsFile read = ReadConstantsFile(base / (staged[i].serial + ".json"));
    EXPECT_EQ(ToJson(read)["constants"], ToJson(one_shot[i])["constants"]);
    EXPECT_EQ(ToJson(read)["standard_errors"], ToJson(one_shot[i])["standard_errors"]);
    // Every stage's recordings, the earlier stages' first.
    EXPECT_EQ(read.provenance.recordings.size(), 3 * one_shot[i].provenance.recordings.size());
  }
  std::filesystem::remove_all(dir);
}

TEST(ImuReferenceFit, StagedFitRefusesAMissingOrShortBaseAndTheJointStrategy) {
  const Runs& runs = SharedRuns();
  const auto dir = std::filesystem::temp_directory_path() /
                   ("adahrs_imu_staged_refusals_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::vector<std::filesystem::path> both = {runs.thermal, runs.sensor};
  EXPECT_THAT(
      [&] {
        FitImuRuns(both, ImuStrategy::Reference(), "t", ImuStageRequest{ImuStage::kSensor, dir});
      },
      ::testing::ThrowsMessage<ImuInputError>(
          ::testing::AllOf(::testing::HasSubstr((dir / "IMU-0001.json").string()),
                           ::testing::HasSubstr("the sensor stage needs"),
                           ::testing::HasSubstr("does not exist"))));
  for (const ConstantsFile& f :
       FitImuRuns(both, ImuStrategy::Reference(), "t", ImuStageRequest{ImuStage::kThermal, {}})) {
    WriteConstantsFile(dir / (f.serial + ".json"), f);
  }
  EXPECT_THAT(
      [&] {
        FitImuRuns(both, ImuStrategy::Reference(), "t", ImuStageRequest{ImuStage::kCrossAxis, dir});
      },
      ::testing::ThrowsMessage<ImuInputError>(
          ::testing::HasSubstr("holds no sensor stage, which the cross_axis stage builds on")));
  EXPECT_THAT(
      [&] {
        FitImuRuns(both, ImuStrategy::JointFormat3(), "t", ImuStageRequest{ImuStage::kThermal, {}});
      },
      ::testing::ThrowsMessage<ImuInputError>(
          ::testing::HasSubstr("the joint strategy fits every stage at once")));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace adahrs::calib
