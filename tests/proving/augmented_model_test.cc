// The augmented unit model (`adahrs diagnose --model`, OUT/model.json): the findings written into
// the simulator's unit schema match the truth the recording came from, and re-simulating the
// recording's stimulus with the augmented model reproduces the recording where the base model
// could not (docs/diagnose.md "The augmented model").
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "calib/ads_calibration/ads_calibration_points.h"
#include "common/param_reader.h"
#include "diagnosis/ads_diagnosis.h"
#include "diagnosis/diagnosis_cells.h"
#include "hil/recording/recording_reader.h"
#include "proving/demo/augmented_model.h"
#include "tests/diagnosis/imu_diagnosis_scenario.h"
#include "tests/support/ads_recording_sim.h"

namespace adahrs::proving {
namespace {

namespace fs = std::filesystem;
using sensor_sim::AdsUnitParams;
using sensor_sim::ImuUnitParams;

fs::path WriteUnitFile(const fs::path& dir, const std::string& kind, const nlohmann::json& params) {
  fs::create_directories(dir);
  const fs::path path = dir / "base.json";
  std::ofstream(path) << nlohmann::json{
      {"kind", kind},
      {"model_profile", "nominal"},
      {"params", params}}.dump(2);
  return path;
}

std::vector<calib::AdsCalibrationPoint> Points(const AdsUnitParams& unit,
                                               const fs::path& run,
                                               uint64_t noise_seed) {
  fs::remove_all(run);
  calib::testing::WriteAdsRecording(
      run, calib::testing::ShippedSequencePath("ads_calibration"), unit, noise_seed);
  std::vector<calib::AdsCalibrationPoint> points =
      calib::SelectAdsCalibrationPoints(hil::ReadRecording(run), unit.serial, run.string());
  fs::remove_all(run);
  return points;
}

// RMS over the points of the static bridge's code difference, in Pa at the nominal sensitivity.
double RmsPa(const std::vector<calib::AdsCalibrationPoint>& a,
             const std::vector<calib::AdsCalibrationPoint>& b,
             double codes_per_pa) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    s += std::pow((a[i].ps_cnt - b[i].ps_cnt) / codes_per_pa, 2);
  return std::sqrt(s / static_cast<double>(a.size()));
}

// An ADS whose bridges have pressure hysteresis the base model lacks: model.json switches it on
// at the fitted loop and span, and the augmented unit, run through the same sequence with the same
// noise, reproduces the recording's static-bridge points to a fraction of the base model's error.
TEST(AugmentedModel, AdsPressureHysteresisReproducesTheRecording) {
  const fs::path dir = fs::temp_directory_path() / "adahrs_augmented_ads";
  fs::remove_all(dir);
  AdsUnitParams base = AdsUnitParams::Draw("ADS-9600", 6600, sensor_sim::ModelProfile::kNominal);
  AdsUnitParams truth = base;
  for (auto* b : {&truth.static_bridge, &truth.pitot_bridge}) b->effects.pressure_hysteresis = true;
  const std::vector<calib::AdsCalibrationPoint> recorded = Points(truth, dir / "truth", 600);
  const diagnosis::UnitDiagnosis d = diagnosis::DiagnoseAds(truth.serial, recorded);
  diagnosis::DiagnosisRun run;
  run.units.push_back(d);
  const AugmentedModel m =
      WriteAugmentedModel(run, WriteUnitFile(dir, "ads", base.ToJson()), dir / "out");
  for (const std::string& a : m.applied) std::printf("applied: %s\n", a.c_str());
  for (const std::string& n : m.not_applied) std::printf("not applied: %s\n", n.c_str());
  const nlohmann::json written = common::ParamReader::LoadFile((dir / "out/model.json").string());
  const AdsUnitParams augmented =
      AdsUnitParams::FromJson(common::ParamReader(written["params"], "model.json", "$.params"));
  ASSERT_TRUE(augmented.static_bridge.effects.pressure_hysteresis);
  const diagnosis::Finding* f = nullptr;
  for (const diagnosis::Finding& x : d.findings) {
    if (x.effect == "pressure_hysteresis" && x.channel == "ps") f = &x;
  }
  ASSERT_NE(f, nullptr);
  // The half loop's standard error: ADS diagnosis bounds it by the truth's scatter over 10 units
  // through the same sequence (AdsDiagnosis.FindsPressureHysteresisFromUpAndDownSweeps).
  const double se_pct =
      2.0 * f->components[0].standard_error / truth.static_bridge.full_scale_pa * 100.0;
  EXPECT_NEAR(augmented.static_bridge.pressure_hysteresis_pct_fso,
              truth.static_bridge.pressure_hysteresis_pct_fso,
              3.0 * se_pct);

  const double codes_per_pa =
      std::abs(recorded.back().ps_cnt - recorded.front().ps_cnt) /
      std::max(1.0, std::abs(recorded.back().ps_ref_pa - recorded.front().ps_ref_pa));
  const double before = RmsPa(recorded, Points(base, dir / "base", 600), codes_per_pa);
  const double after = RmsPa(recorded, Points(augmented, dir / "augmented", 600), codes_per_pa);
  // The yardstick: the true unit itself, re-run with fresh noise, leaves this much.
  const double fresh_noise = RmsPa(recorded, Points(truth, dir / "fresh", 601), codes_per_pa);
  std::printf(
      "static bridge points, re-simulated: RMS %.2f Pa with the base model, %.2f Pa with "
      "model.json; the truth with fresh noise %.2f Pa\n",
      before,
      after,
      fresh_noise);
  // docs/diagnose.md: reproduced to 0.06 Pa RMS against 32.8 Pa. Asserted below 0.1 Pa and below
  // half of what the true unit with fresh noise leaves: the augmented model is closer to the
  // recording than the unit itself on another run. A loop 1 % high leaves 0.39 Pa.
  EXPECT_GT(before, 30.0);
  EXPECT_LT(after, 0.1);
  EXPECT_LT(after, 0.5 * fresh_noise);
  fs::remove_all(dir);
}

// An IMU with gyro g-sensitivity the base model lacks: model.json carries it in each gyro's
// package frame, within 3 standard errors (the finding's, in B) of the truth. The recording is
// unit 5 of ImuDiagnosis.FindsGyroGSensitivityConcealedAsOrientationBias (same unit, noise and
// shape), whose standard errors that test bounds by the truth's scatter over its 10 units.
TEST(AugmentedModel, ImuGyroGSensitivityInThePackageFrame) {
  ImuUnitParams base = ImuUnitParams::Draw("IMU-0001", 105, sensor_sim::ModelProfile::kNominal);
  ImuUnitParams truth = base;
  for (auto& g : truth.gyros) g.effects.g_sensitivity = true;
  diagnosis::testing::ImuScenario s(truth, 2005, 25.0);
  s.ThermalProfile(31, {-20.0, 70.0, 25.0}, 10.0, 300.0);
  s.Soak(25.0, 1.0);
  s.SensorCalibration(2, 500, 300);
  const diagnosis::UnitDiagnosis d =
      diagnosis::DiagnoseImu(diagnosis::BuildDiagnosisData(s.data(), 9.80665));
  diagnosis::DiagnosisRun run;
  run.units.push_back(d);
  const fs::path dir = fs::temp_directory_path() / "adahrs_augmented_imu";
  fs::remove_all(dir);
  const AugmentedModel m =
      WriteAugmentedModel(run, WriteUnitFile(dir, "imu", base.ToJson()), dir / "out");
  for (const std::string& a : m.applied) std::printf("applied: %s\n", a.c_str());
  const nlohmann::json written = common::ParamReader::LoadFile((dir / "out/model.json").string());
  const ImuUnitParams augmented =
      ImuUnitParams::FromJson(common::ParamReader(written["params"], "model.json", "$.params"));
  int checked = 0;
  for (const diagnosis::Finding& f : d.findings) {
    if (f.effect != "gyro_g_sensitivity") continue;
    const int g = f.channel == "gx" ? 0 : f.channel == "gy" ? 1 : 2;
    ASSERT_TRUE(augmented.gyros[g].effects.g_sensitivity);
    const Eigen::Vector3d got(augmented.gyros[g].g_sensitivity_dps_per_g.data());
    const Eigen::Vector3d want(truth.gyros[g].g_sensitivity_dps_per_g.data());
    double se2 = 0.0;
    for (const diagnosis::FindingComponent& c : f.components)
      se2 += c.standard_error * c.standard_error;
    EXPECT_LE((got - want).norm(), 3.0 * std::sqrt(se2)) << f.channel;
    ++checked;
  }
  EXPECT_GE(checked, 2);
  fs::remove_all(dir);
}

// A base file of another unit is refused naming its serial.
TEST(AugmentedModel, RefusesABaseFileOfAnotherUnit) {
  const fs::path dir = fs::temp_directory_path() / "adahrs_augmented_other";
  fs::remove_all(dir);
  diagnosis::DiagnosisRun run;
  run.units.push_back(diagnosis::UnitDiagnosis{});
  run.units[0].serial = "ADS-0002";
  const fs::path base = WriteUnitFile(
      dir, "ads", AdsUnitParams::Draw("ADS-0001", 1, sensor_sim::ModelProfile::kNominal).ToJson());
  try {
    WriteAugmentedModel(run, base, dir / "out");
    ADD_FAILURE() << "accepted";
  } catch (const common::ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("'ADS-0001' is not a unit of the diagnosed recordings"),
              std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace adahrs::proving
