// The improved (joint) strategy against the truth on simulated units with the reference hardware
// magnitudes (ModelProfile::kNominal), recordings made by the recording maker (short: 300 packets
// per acquisition, thermal profile compressed 60x — exact without die lag, and the CRB accounts
// for the length).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/imu_calibration/imu_strategy.h"
#include "common/gravity.h"
#include "common/median.h"
#include "proving/evaluation/imu_evaluation.h"
#include "tests/support/twenty_nominal_imus.h"

namespace adahrs::calib {
namespace {

using sensor_sim::ImuUnitParams;

const double kGLocal_mps2 = common::NormalGravityMps2(32.6, 200.0);

std::string Verdict(const proving::ImuEvaluation& e, const std::string& quantity) {
  return e.report[quantity]["verdict"].get<std::string>();
}

// Required: on >= 20 units the improved strategy's evaluated worst errors are within the
// specification or within 1.5x the CRB-implied limit, and the evaluation says which.
// With the firmware's cubic thermal term and the exporter's span normalisation every unit exports
// and the firmware floor is far below the specification (accel ~0.1-0.2 mg, rate ~0.005 deg/s).
// Acceleration: within the specification on all 20 units (0.15-0.29 mg against 1.0 mg).
// Body rate: the gyro bias instability (75 deg/h floor, correlation times up to 5000 s) wanders
// by more than the specification over a calibration run, and no static calibration averages its
// slow part away in a run this long. The joint strategy fits the gyros by generalised least
// squares with that wander's covariance between observations (gyro_bias_covariance.h) and the CRB
// uses the same covariance: all 20 units within 1.5x the CRB limit (worst 0.08-0.19 deg/s against
// a per-point 3-sigma limit of 0.11-0.15; reference strategy 0.34-1.04 deg/s). The bound is
// checked against the truth, not only used: the gyro nulls' and thermal coefficients' errors are
// about one CRB standard deviation (median over the units of their RMS error / CRB se 0.95).
TEST(ImuJointFit, TwentyUnitsWithinSpecOrCrbLimit) {
  const auto base = std::filesystem::temp_directory_path() / "adahrs_imu_joint_twenty";
  std::map<std::string, int> verdicts;
  double sum_joint = 0.0, sum_reference = 0.0;
  std::vector<double> gyro_error_over_crb;
  testing::ForEachNominalImuBatch(
      base,
      kGLocal_mps2,
      sensor_sim::TruthVariant::kStandard,
      [&](const std::vector<ImuUnitParams>& params,
          const std::filesystem::path& thermal,
          const std::filesystem::path& sensor) {
        const auto joint = FitImuRuns({thermal, sensor}, ImuStrategy::JointFormat2(), "test");
        const auto reference = FitImuRuns({thermal, sensor}, ImuStrategy::Reference(), "test");
        ASSERT_EQ(joint.size(), 4u);
        proving::ImuEvaluationOptions options;
        options.g_local_mps2 = kGLocal_mps2;
        options.frames = 40;
        for (size_t u = 0; u < 4; ++u) {
          SCOPED_TRACE(params[u].serial);
          proving::ImuEvaluation e, r;
          try {
            e = proving::EvaluateImu(joint[u], params[u], Specification::Reference(), options);
            r = proving::EvaluateImu(reference[u], params[u], Specification::Reference(), options);
          } catch (const proving::ConstantsNotExportable& error) {
            ADD_FAILURE() << params[u].serial << " not exportable: " << error.what();
            continue;
          }
          for (const char* q : {"acceleration", "body_rate"})
            ++verdicts[std::string(q) + ": " + Verdict(e, q)];
          EXPECT_EQ(Verdict(e, "acceleration"), "within specification")
              << e.report["acceleration"].dump();
          EXPECT_LT(e.worst_rate_dps, r.worst_rate_dps);
          sum_joint += e.worst_accel_mg / 1.0 + e.worst_rate_dps / 0.015;
          sum_reference += r.worst_accel_mg / 1.0 + r.worst_rate_dps / 0.015;
          gyro_error_over_crb.push_back(testing::GyroErrorOverCrb(e));
          std::printf(
              "%s joint accel %.3f mg (floor %.3f) rate %.4f dps (floor %.4f, CRB limit %.4f, "
              "gyro error/CRB se %.2f) | reference %.3f mg %.4f dps\n",
              params[u].serial.c_str(),
              e.worst_accel_mg,
              e.report["acceleration"]["worst_firmware_floor_mg"].get<double>(),
              e.worst_rate_dps,
              e.report["body_rate"]["worst_firmware_floor_dps"].get<double>(),
              e.report["body_rate"]["crb_limit_dps_at_worst"].get<double>(),
              gyro_error_over_crb.back(),
              r.worst_accel_mg,
              r.worst_rate_dps);
        }
      });
  for (const auto& [v, n] : verdicts) std::printf("%2d x %s\n", n, v.c_str());
  EXPECT_LE(sum_joint, sum_reference);
  EXPECT_EQ(verdicts["body_rate: within specification"] +
                verdicts["body_rate: outside specification, within 1.5x the physical limit"],
            20);
  // An inflated bound would pass the verdict trivially; an optimistic one would fail it by luck.
  ASSERT_EQ(gyro_error_over_crb.size(), 20u);
  const double median_error_over_crb = common::Median(gyro_error_over_crb);
  std::printf("median gyro error / CRB se %.2f\n", median_error_over_crb);
  EXPECT_GT(median_error_over_crb, 0.5);
  EXPECT_LT(median_error_over_crb, 2.0);
}

}  // namespace
}  // namespace adahrs::calib
