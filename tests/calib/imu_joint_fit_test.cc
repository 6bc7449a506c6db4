// The improved (joint) strategy against the truth on simulated units with the reference hardware
// magnitudes (ModelProfile::kNominal), recordings made by the recording maker (short: 300 packets
// per acquisition, thermal profile compressed 60x — exact without die lag, and the CRB accounts
// for the length).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/evaluation/imu_evaluation.h"
#include "calib/imu_calibration/imu_strategy.h"
#include "imu_recording_maker.h"
#include "sensor_sim/gravity.h"

namespace adahrs::calib {
namespace {

using sensor_sim::ImuUnitParams;

const double kGLocal_mps2 = sensor_sim::NormalGravityMps2(32.6, 200.0);

std::string Verdict(const ImuEvaluation& e, const std::string& quantity) {
  return e.report[quantity]["verdict"].get<std::string>();
}

// Issue 6 done-when: on >= 20 units the improved strategy's evaluated worst errors are within
// the specification or within 1.5x the CRB-implied limit, and the evaluation says which.
// NOT MET as stated, and the evaluation shows why: the simulated drift has cubic terms (zero-g
// b3 sigma 5e-5 mg/degC^3, null tc3 sigma 1e-5 deg/s/degC^3, docs/models/) that the firmware's
// quadratic thermal term cannot hold over -40...+85 degC: the best constants the firmware can
// hold (the firmware floor) already miss the specification by several mg and tenths of deg/s.
// What is tested: every verdict is one of the evaluation's categories; a unit judged "outside"
// has a firmware floor (or an exporter refusal) that by itself misses the specification, i.e.
// no calibration into these constants could pass; the improved strategy is no worse than the
// reference summed over the units.
TEST(ImuJointFit, TwentyUnitsWithinSpecOrCrbOrFirmwareFloor) {
  const auto base = std::filesystem::temp_directory_path() / "adahrs_imu_joint_twenty";
  testing::MakerOptions maker_options;
  maker_options.thermal_speedup = 60.0;
  std::map<std::string, int> verdicts;
  double sum_joint = 0.0, sum_reference = 0.0;
  for (int batch = 0; batch < 5; ++batch) {
    std::vector<ImuUnitParams> params;
    for (int i = 0; i < 4; ++i) {
      const int n = 4 * batch + i + 1;
      params.push_back(ImuUnitParams::Draw("IMU-" + std::string(n < 10 ? "000" : "00") + std::to_string(n),
                                           500 + n, sensor_sim::ModelProfile::kNominal));
    }
    testing::ImuRecordingMaker maker(params, kGLocal_mps2, 900 + batch, maker_options);
    const auto thermal = base / ("thermal" + std::to_string(batch));
    const auto sensor = base / ("sensor" + std::to_string(batch));
    maker.Run(testing::ShippedSequence("imu_thermal_calibration_full", 300), thermal);
    maker.Run(testing::ShippedSequence("imu_sensor_calibration", 300), sensor);
    const auto joint = FitImuRuns({thermal, sensor}, ImuStrategy::Improved(), "test");
    const auto reference = FitImuRuns({thermal, sensor}, ImuStrategy::Reference(), "test");
    ASSERT_EQ(joint.size(), 4u);
    ImuEvaluationOptions options;
    options.g_local_mps2 = kGLocal_mps2;
    options.frames = 40;
    for (size_t u = 0; u < 4; ++u) {
      SCOPED_TRACE(params[u].serial);
      ImuEvaluation e, r;
      try {
        e = EvaluateImu(joint[u], params[u], Specification::Reference(), options);
        r = EvaluateImu(reference[u], params[u], Specification::Reference(), options);
      } catch (const ConstantsNotExportable& error) {
        // The exporter's uint16-wide temperature normalisation cannot hold this unit's drift.
        EXPECT_THAT(error.what(), ::testing::HasSubstr("cannot be exported to the firmware"));
        ++verdicts["not exportable"];
        std::printf("%s not exportable: %s\n", params[u].serial.c_str(), error.what());
        continue;
      }
      for (const char* q : {"acceleration", "body_rate"}) {
        const std::string v = Verdict(e, q);
        ++verdicts[std::string(q) + ": " + v];
        if (v == "outside") {
          const std::string floor_key = std::string("worst_firmware_floor_") + (q[0] == 'a' ? "mg" : "dps");
          const double floor = e.report[q][floor_key].get<double>();
          const double spec = q[0] == 'a' ? 1.0 : 0.015;
          EXPECT_TRUE(std::isnan(floor) || floor > spec) << e.report[q].dump();
        }
      }
      sum_joint += e.worst_accel_mg / 1.0 + e.worst_rate_dps / 0.015;
      sum_reference += r.worst_accel_mg / 1.0 + r.worst_rate_dps / 0.015;
      std::printf("%s joint accel %.3f mg (floor %.3f) rate %.4f dps (floor %.4f) | reference %.3f mg %.4f dps\n",
                  params[u].serial.c_str(), e.worst_accel_mg,
                  e.report["acceleration"]["worst_firmware_floor_mg"].get<double>(), e.worst_rate_dps,
                  e.report["body_rate"]["worst_firmware_floor_dps"].get<double>(), r.worst_accel_mg,
                  r.worst_rate_dps);
    }
    std::filesystem::remove_all(thermal);
    std::filesystem::remove_all(sensor);
  }
  for (const auto& [v, n] : verdicts) std::printf("%2d x %s\n", n, v.c_str());
  EXPECT_LE(sum_joint, sum_reference);
  // Most units must reach the evaluation: the exporter's uint16-wide temperature normalisation
  // refuses 7 of these 20 today (a known firmware_model defect), and a change that refused more
  // would otherwise pass unseen.
  EXPECT_LE(verdicts["not exportable"], 7);
}

}  // namespace
}  // namespace adahrs::calib
