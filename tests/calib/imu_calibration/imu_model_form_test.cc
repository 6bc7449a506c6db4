// The joint IMU strategy's gyro fit when the truth's bias wander is not the calibration's prior:
// the 20 nominal units of ImuJointFit.TwentyUnitsWithinSpecOrCrbLimit under two truths side by
// side, each fitted with the wander's covariance from the datasheet prior (floor 75 deg/h, poles
// at 5...5,000 s) and estimated from the recording (gyro_wander_fit.h), and evaluated against
// the truth through the firmware.
//   matched:          the truth's flicker has the prior's form (rate random walk off, nominal);
//   slow bias wander: poles ten times slower and a rate random walk three times the drawn one
//                     (sensor_sim TruthVariant::kSlowBiasWander).
// Printed per column: the body-rate verdicts, the worst rate error, the CRB-implied limit, and the
// median over the units of the gyro parameters' RMS error / CRB standard error (about 1 when the
// bound is honest; far above 1 when the covariance is optimistic). docs/calibration-strategies.md
// "Model-form mismatch" quotes them.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "calib/constants/imu_fit_diagnostics.h"
#include "calib/imu_calibration/imu_strategy.h"
#include "common/gravity.h"
#include "common/median.h"
#include "proving/evaluation/imu_evaluation.h"
#include "tests/support/sanitized_units.h"
#include "tests/support/twenty_nominal_imus.h"

namespace adahrs::calib {
namespace {

using sensor_sim::ImuUnitParams;

const double kGLocal_mps2 = common::NormalGravityMps2(32.6, 200.0);

struct Column {
  std::map<std::string, int> verdicts;
  std::vector<double> error_over_crb, rate_dps, limit_dps, floor_dph, time_scale, white_scale;
};

// The figures asserted below are those of the seeded 20 units and cannot be drawn on fewer; under
// the sanitizers (about 2 min per test on the 2-core VM) the two tests are skipped, visibly: the
// release pass holds the figures; under the sanitizers the joint fit and its evaluation run in
// ImuJointFit, the wander's estimation in gyro_wander_fit_test.cc.
constexpr const char* kSkippedUnderSanitizers =
    "the 20 seeded units' figures are the release pass's (tests/support/sanitized_units.h)";

// [0]: the datasheet prior; [1]: estimated from the recording.
std::array<Column, 2> RunTwentyUnits(sensor_sim::TruthVariant variant) {
  std::array<Column, 2> c;
  // One directory per truth: ctest runs the tests side by side.
  const auto base = std::filesystem::temp_directory_path() /
                    ("adahrs_imu_model_form_" + sensor_sim::ToString(variant));
  testing::ForEachNominalImuBatch(
      base,
      kGLocal_mps2,
      variant,
      [&](const std::vector<ImuUnitParams>& params,
          const std::filesystem::path& thermal,
          const std::filesystem::path& sensor) {
        for (int k = 0; k < 2; ++k) {
          ImuStrategy strategy = ImuStrategy::JointFormat2();
          strategy.estimate_gyro_wander = k == 1;
          const auto fits = FitImuRuns({thermal, sensor}, strategy, "test");
          proving::ImuEvaluationOptions options;
          options.g_local_mps2 = kGLocal_mps2;
          options.frames = 40;
          for (size_t u = 0; u < fits.size(); ++u) {
            const proving::ImuEvaluation e =
                proving::EvaluateImu(fits[u], params[u], Specification::Reference(), options);
            ++c[k].verdicts[e.report["body_rate"]["verdict"].get<std::string>()];
            c[k].error_over_crb.push_back(testing::GyroErrorOverCrb(e));
            c[k].rate_dps.push_back(e.worst_rate_dps);
            c[k].limit_dps.push_back(e.report["body_rate"]["crb_limit_dps_at_worst"].get<double>());
            ASSERT_TRUE(fits[u].imu_diagnostics.has_value());
            const ImuFitDiagnostics& diag = *fits[u].imu_diagnostics;
            ASSERT_TRUE(diag.joint.has_value());
            for (const char* g : {"gx", "gy", "gz"}) {
              const auto& w = diag.joint->channels.at(g).bias_wander;
              ASSERT_TRUE(w.has_value()) << g;
              c[k].floor_dph.push_back(w->floor_dph);
              c[k].time_scale.push_back(w->time_scale);
              if (k == 1) c[k].white_scale.push_back(w->white_variance_scale.value());
            }
          }
        }
      });
  for (int k = 0; k < 2; ++k) {
    const Column& col = c[k];
    std::printf(
        "%s, wander %s: median gyro error / CRB se %.2f (max %.2f); worst rate %.3f-%.3f "
        "deg/s against CRB limits %.3f-%.3f; gyro floor median %.0f deg/h, time scale "
        "median %.1f\n",
        sensor_sim::ToString(variant).c_str(),
        k == 0 ? "datasheet" : "estimated",
        common::Median(col.error_over_crb),
        *std::max_element(col.error_over_crb.begin(), col.error_over_crb.end()),
        *std::min_element(col.rate_dps.begin(), col.rate_dps.end()),
        *std::max_element(col.rate_dps.begin(), col.rate_dps.end()),
        *std::min_element(col.limit_dps.begin(), col.limit_dps.end()),
        *std::max_element(col.limit_dps.begin(), col.limit_dps.end()),
        common::Median(col.floor_dph),
        common::Median(col.time_scale));
    if (!col.white_scale.empty())
      std::printf("  white variance scale median %.2f\n", common::Median(col.white_scale));
    for (const auto& [v, n] : col.verdicts) std::printf("  %2d x body rate %s\n", n, v.c_str());
  }
  return c;
}

int WithinSpecOrBound(const Column& c) {
  auto count = [&](const char* v) { return c.verdicts.count(v) ? c.verdicts.at(v) : 0; };
  return count("within specification") +
         count("outside specification, within 1.5x the physical limit");
}

// The figures docs/calibration-strategies.md ("Model-form mismatch") states, asserted as it
// prints them: the units, their noise and the fits are seeded, so each run gives the same
// figures. A median within 0.01 of the docs' two decimals (half a unit of the last for their
// rounding, as much again for another compiler's libm), a count exactly: a figure further off is
// a changed calibration that the docs must follow. The window "about 1" would not do: it admits
// the 1.17 the docs call optimistic by a sixth.
constexpr double kMedianTolerance = 0.01;

// Matched: datasheet prior median 0.95, 20 of 20 within 1.5x the bound; estimated median 1.09,
// 19 of 20, the white variances found 1.4 times the datasheet's and the time scale at the
// search's fast end (the test's thermal profile is compressed 60x: the slow poles are one offset
// over the run, which the null absorbs).
TEST(ImuModelForm, MatchedWanderBothCovariancesGiveAnHonestBound) {
  if (adahrs::testing::kSanitized) GTEST_SKIP() << kSkippedUnderSanitizers;
  const std::array<Column, 2> c = RunTwentyUnits(sensor_sim::TruthVariant::kStandard);
  EXPECT_NEAR(common::Median(c[0].error_over_crb), 0.95, kMedianTolerance);
  EXPECT_NEAR(common::Median(c[1].error_over_crb), 1.09, kMedianTolerance);
  EXPECT_EQ(WithinSpecOrBound(c[0]), 20);
  EXPECT_EQ(WithinSpecOrBound(c[1]), 19);
  EXPECT_NEAR(common::Median(c[1].white_scale), 1.4, 0.05 + kMedianTolerance);
}

// Slower wander than the prior: datasheet prior median 1.17, 18 of 20 within 1.5x the bound;
// estimated median 1.38, 15 of 20, its time scale 3 (the truth's 10). The recording's
// observation means do not identify the slower wander well enough to tighten the bound, so the
// datasheet prior stays the default; a bound optimistic by a sixth is what the mismatch costs it.
TEST(ImuModelForm, SlowerWanderThanThePrior) {
  if (adahrs::testing::kSanitized) GTEST_SKIP() << kSkippedUnderSanitizers;
  const std::array<Column, 2> c = RunTwentyUnits(sensor_sim::TruthVariant::kSlowBiasWander);
  EXPECT_NEAR(common::Median(c[0].error_over_crb), 1.17, kMedianTolerance);
  EXPECT_EQ(WithinSpecOrBound(c[0]), 18);
  EXPECT_NEAR(common::Median(c[1].error_over_crb), 1.38, kMedianTolerance);
  EXPECT_EQ(WithinSpecOrBound(c[1]), 15);
  // It moves toward the truth's slower poles, to 3 (the docs' one digit: within 0.5).
  EXPECT_NEAR(common::Median(c[1].time_scale), 3.0, 0.5);
}

}  // namespace
}  // namespace adahrs::calib
