// The held-out check of a diagnosis by re-simulation (diagnosis/replay_comparison.h with
// `adahrs simulate replay`): an ADS whose bridges have pressure hysteresis its model lacks is
// diagnosed on its calibration run; its acceptance run, which the diagnosis never saw, re-simulated
// with the augmented model.json is reproduced far better than with the base model. And the
// comparison's own arithmetic on rows whose means are known.
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "calib/ads_calibration/ads_calibration_points.h"
#include "diagnosis/ads_diagnosis.h"
#include "diagnosis/replay_check_report.h"
#include "diagnosis/replay_comparison.h"
#include "hil/recording/recording_reader.h"
#include "hil/recording/recording_writer.h"
#include "proving/demo/augmented_model.h"
#include "tests/support/ads_recording_sim.h"

namespace adahrs::proving {
namespace {

namespace fs = std::filesystem;

fs::path TempDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("adahrs_replay_check_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// `adahrs simulate replay`, the command a user runs, as the replay function.
void ReplayWithTheCommand(const fs::path& run,
                          const std::vector<fs::path>& files,
                          const fs::path& out) {
  std::string cmd = std::string(std::getenv("ADAHRS_BIN_DIR")) + "/adahrs simulate replay --run '" +
                    run.string() + "' --out '" + out.string() + "' --seed 77";
  for (const fs::path& f : files) cmd += " --unit '" + f.string() + "'";
  ASSERT_EQ(std::system((cmd + " > /dev/null").c_str()), 0) << cmd;
}

void WriteUnitFile(const fs::path& path, const sensor_sim::AdsUnitParams& p) {
  std::ofstream(path) << nlohmann::json{
      {"kind", "ads"},
      {"model_profile", "nominal"},
      {"params", p.ToJson()}}.dump(2);
}

TEST(ReplayCheck, AHeldOutRunIsReproducedWithTheFoundHysteresis) {
  const fs::path dir = TempDir("ads");
  sensor_sim::AdsUnitParams base =
      sensor_sim::AdsUnitParams::Draw("ADS-0007", 6607, sensor_sim::ModelProfile::kNominal);
  sensor_sim::AdsUnitParams truth = base;
  for (auto* b : {&truth.static_bridge, &truth.pitot_bridge}) b->effects.pressure_hysteresis = true;
  calib::testing::WriteAdsRecording(
      dir / "calibration", calib::testing::ShippedSequencePath("ads_calibration"), truth, 601);
  calib::testing::WriteAdsRecording(
      dir / "acceptance", calib::testing::ShippedSequencePath("ads_acceptance"), truth, 602);
  const diagnosis::UnitDiagnosis d = diagnosis::DiagnoseAds(
      truth.serial,
      calib::SelectAdsCalibrationPoints(
          hil::ReadRecording(dir / "calibration"), truth.serial, "calibration"));
  diagnosis::DiagnosisRun run;
  run.units.push_back(d);
  WriteUnitFile(dir / "base.json", base);
  const AugmentedModel m = WriteAugmentedModel(run, dir / "base.json", dir / "out");
  for (const std::string& a : m.applied) std::printf("applied: %s\n", a.c_str());
  for (const auto* b : {&truth.static_bridge, &truth.pitot_bridge}) {
    std::printf("truth: pressure_hysteresis_pct_fso %.4g, span %.4g %% FS\n",
                b->pressure_hysteresis_pct_fso,
                b->pressure_hysteresis_span_pct_fs);
  }

  const diagnosis::ReplayComparison c = diagnosis::CheckByReplay(dir / "acceptance",
                                                                 {dir / "base.json"},
                                                                 {dir / "out/model.json"},
                                                                 dir / "replay",
                                                                 true,
                                                                 ReplayWithTheCommand);
  ASSERT_EQ(c.units.size(), 1u);
  ASSERT_EQ(c.units[0].channels.size(), 2u);
  for (const diagnosis::ChannelReplayFit& ch : c.units[0].channels) {
    std::printf(
        "%s: held-out RMS %.2f Pa with the base model, %.2f with model.json, noise alone %.2f (%zu "
        "acquisitions)\n",
        ch.channel.c_str(),
        ch.rms_base,
        ch.rms_model,
        ch.rms_noise,
        ch.acquisitions.size());
    EXPECT_EQ(ch.unit, "Pa");
    EXPECT_GT(ch.acquisitions.size(), 20u);
  }
  const diagnosis::ChannelReplayFit& ps = c.units[0].channels[0];
  EXPECT_EQ(ps.channel, "ps");
  // The static bridge's loop is found within a few percent: what remains is the noise's; the
  // pitot's, found within 3 % (its span 0.4 % short), leaves a fortieth of its error.
  EXPECT_GT(ps.rms_base, 10.0 * ps.rms_noise);
  EXPECT_LT(ps.rms_model, 3.0 * ps.rms_noise);
  EXPECT_LT(c.units[0].channels[1].rms_model, 0.05 * c.units[0].channels[1].rms_base);
  WriteUnitFile(dir / "truth.json", truth);
  const diagnosis::ReplayComparison t = diagnosis::CheckByReplay(dir / "acceptance",
                                                                 {dir / "truth.json"},
                                                                 {dir / "truth.json"},
                                                                 dir / "replay_truth",
                                                                 true,
                                                                 ReplayWithTheCommand);
  for (const diagnosis::ChannelReplayFit& ch : t.units[0].channels) {
    std::printf("%s: held-out RMS %.2f Pa with the truth\n", ch.channel.c_str(), ch.rms_base);
    // The replay itself: the truth reproduces the run to its noise (the run starts at 0 °C, which
    // is a temperature, not an instrument that has not reported).
    EXPECT_LT(ch.rms_base, 2.0 * ch.rms_noise) << ch.channel;
  }
  diagnosis::WriteReplayCheck({c}, dir / "out");
  std::ifstream html_file(dir / "out/replay_check.html");
  const std::string html((std::istreambuf_iterator<char>(html_file)),
                         std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("ADS-0007 ps: mean residual of each acquisition"),
            std::string::npos);  // its figure
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(
                dir / "out/replay_check.json"))[0]["units"][0]["channels"][0]["rms_model"],
            ps.rms_model);
  const hil::Recording meta = hil::ReadRecordingMeta(dir / "replay/model");
  EXPECT_EQ(meta.meta.extra["replay"]["noise"], 77);
  fs::remove_all(dir);
}

// Rows of known means: the comparison's differences, RMS and unit conversions are those means'.
TEST(ReplayCheck, ComparesAcquisitionMeansInPhysicalUnits) {
  const fs::path dir = TempDir("means");
  // Recorded gx 20971.52 counts (1 °/s) above the base replay and 2097.152 (0.1 °/s) above the
  // model's; az1 duty 0.5 + 0.04 (1 g) recorded, the replays 0.5 + 0.04 + 0.0004 (10 mg more).
  auto write = [&](const fs::path& run, int32_t gx, uint16_t az1_t1) {
    hil::RecordingWriter w(run);
    w.WriteMetaJson({{"run_id", "means"},
                     {"status", "complete"},
                     {"units", {{{"kind", "imu"}, {"serial", "IMU-0001"}}}}});
    hil::ImuRecordRow row;
    row.unit = "IMU-0001";
    for (int step = 1; step <= 2; ++step) {
      for (int i = 0; i < 100; ++i) {
        row.t_s = step * 10.0 + i * 0.01;
        row.step = step;
        row.tag = static_cast<uint8_t>(step);
        row.accel_ticks.fill(10000);
        row.accel_ticks[0] = az1_t1;
        row.accel_ticks[1] = 10000;
        row.gyro_cnt = {gx + (i % 2 == 0 ? 500 : -500), 0, 0};
        w.Append(row);
      }
    }
    w.Flush(true);
  };
  write(dir / "rec", 4000000 + 20972, 5400);
  write(dir / "base", 4000000, 5404);
  write(dir / "model", 4000000 + 20972 - 2097, 5404);
  const diagnosis::ReplayComparison c =
      diagnosis::CompareReplays(dir / "rec", dir / "base", dir / "model", false);
  ASSERT_EQ(c.units.size(), 1u);
  const auto& channels = c.units[0].channels;
  ASSERT_EQ(channels.size(), 9u);
  EXPECT_EQ(channels[0].channel, "az1");
  EXPECT_EQ(channels[0].unit, "mg");
  EXPECT_NEAR(channels[0].rms_base, 10.0, 1e-6);
  EXPECT_EQ(channels[0].acquisitions.size(), 2u);
  EXPECT_NEAR(channels[0].acquisitions[0].base, -10.0, 1e-6);
  EXPECT_EQ(channels[6].channel, "gx");
  EXPECT_EQ(channels[6].unit, "deg/s");
  EXPECT_NEAR(channels[6].rms_base, 20972.0 / 20971.52, 1e-9);
  EXPECT_NEAR(channels[6].rms_model, 2097.0 / 20971.52, 1e-9);
  // Rows alternate ±500 counts: each mean has a standard error of 500/√99·√(100/100)/√100.
  const double se_one = 500.0 * std::sqrt(100.0 / 99.0) / 10.0 / 20971.52;
  EXPECT_NEAR(channels[6].rms_noise, se_one * std::sqrt(2.0), 1e-9);
  EXPECT_EQ(channels[6].acquisitions[1].label, "step 2 tag 2");
  EXPECT_THROW(diagnosis::CompareReplays(dir / "rec", dir / "missing", dir / "model", false),
               hil::RecordingError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace adahrs::proving
