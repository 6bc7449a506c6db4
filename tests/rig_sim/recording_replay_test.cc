// Re-simulation of a recording's stimulus (rig_sim/recording_replay.h): against a recording the
// simulator made of every frame, the unit's own truth file and noise reproduce it, another model
// does not, and bad unit files and instruments that had not reported yet are handled by name.
#include "rig_sim/recording_replay.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/param_reader.h"
#include "hil/recording/recording_reader.h"
#include "hil/recording/recording_writer.h"
#include "rig_sim/static_thermal_run.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::rig_sim {
namespace {

namespace fs = std::filesystem;

fs::path TempDir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("adahrs_replay_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

// A recording of every frame of one IMU and one ADS through a 25 -> 35 °C ramp and a soak.
fs::path RecordEveryFrame(const fs::path& dir) {
  StaticThermalRunConfig config;
  config.imu_units = 1;
  config.ads_units = 1;
  config.log_every = 1;
  config.steps = {{35.0, 10.0, 120.0}};
  RunStaticThermal(config, dir / "rec");
  return dir / "rec";
}

struct Differences {
  double max_gyro_cnt = 0.0, max_temp_cnt = 0.0, max_t1_ticks = 0.0, max_ps_cnt = 0.0;
  double mean_gyro_cnt = 0.0;  // recorded minus replayed, gx
  // The mean's standard error by batch means: the rows in kBatches runs of consecutive rows, the
  // scatter of the runs' means over sqrt(kBatches). Each run spans seconds, far longer than the
  // gyro noise's correlation, so the batches are independent where the rows are not.
  double se_mean_gyro_cnt = 0.0;
};

constexpr size_t kBatches = 50;

// Row by row, IMU-0001's and ADS-0001's outputs of `a` against those of `b` (same rows, same
// order).
Differences Compare(const hil::Recording& a, const hil::Recording& b) {
  Differences d;
  EXPECT_EQ(a.imu.size(), b.imu.size());
  const size_t n = std::min(a.imu.size(), b.imu.size());
  for (size_t i = 0; i < n; ++i) {
    const hil::ImuRecordRow &x = a.imu[i], &y = b.imu[i];
    EXPECT_EQ(x.t_s, y.t_s);
    for (size_t k = 0; k < 3; ++k) {
      d.max_gyro_cnt = std::max(d.max_gyro_cnt, std::abs(double(x.gyro_cnt[k]) - y.gyro_cnt[k]));
      d.max_temp_cnt = std::max(d.max_temp_cnt, std::abs(double(x.temp_cnt[k]) - y.temp_cnt[k]));
    }
    for (size_t k = 0; k < 12; k += 2) {
      d.max_t1_ticks =
          std::max(d.max_t1_ticks, std::abs(double(x.accel_ticks[k]) - y.accel_ticks[k]));
    }
    d.mean_gyro_cnt += (double(x.gyro_cnt[0]) - y.gyro_cnt[0]) / static_cast<double>(n);
  }
  const size_t per_batch = n / kBatches;
  std::vector<double> batch_mean(kBatches, 0.0);
  for (size_t i = 0; i < per_batch * kBatches; ++i) {
    batch_mean[i / per_batch] += (double(a.imu[i].gyro_cnt[0]) - b.imu[i].gyro_cnt[0]) / per_batch;
  }
  double grand = 0.0, var = 0.0;
  for (double m : batch_mean) grand += m / kBatches;
  for (double m : batch_mean) var += (m - grand) * (m - grand) / (kBatches - 1);
  d.se_mean_gyro_cnt = std::sqrt(var / kBatches);
  for (size_t i = 0; i < std::min(a.ads.size(), b.ads.size()); ++i) {
    d.max_ps_cnt = std::max(d.max_ps_cnt, std::abs(double(a.ads[i].ps_cnt) - b.ads[i].ps_cnt));
  }
  return d;
}

// The standard deviation, in counts, of the mean gx difference between two noise draws of one unit
// over `length_s` from the same start: the bias-instability processes (docs/models/adxrs150.md:
// four Gauss-Markov processes, 5 ... 5000 s, of equal variance q^2 set so that their analytic Allan
// deviation averaged in log tau over 10 ... 5000 s is the floor B; each starts at zero) and the
// rate random walk (K, from zero), each draw's mean independent; plus the rows' own scatter
// `se_rows_cnt`. A zero-started process x of variance q^2 and time T has mean over L with
// variance (2 q^2 T / L^2) [L - 2T (1 - e^(-L/T)) + T/2 (1 - e^(-2L/T))]; a walk K^2 L / 3.
double FreshNoiseMeanSdCnt(const fs::path& truth, double length_s, double se_rows_cnt) {
  const nlohmann::json g = common::ParamReader::LoadFile(truth.string())["params"]["gyros"][0];
  const double b_dps = g["effects"]["bias_instability"].get<bool>()
                           ? g["bias_instability_dph"].get<double>() / 3600.0
                           : 0.0;
  const double k_dps_rts = g["effects"]["rate_random_walk"].get<bool>()
                               ? g["rate_random_walk_dph_per_rth"].get<double>() / 3600.0 / 60.0
                               : 0.0;
  const double poles_s[] = {5.0, 50.0, 500.0, 5000.0};
  // The sum's Allan deviation per unit q, averaged in log tau over the band.
  double adev_per_q = 0.0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const double tau = 10.0 * std::pow(500.0, (i + 0.5) / n);
    double avar = 0.0;
    for (double t : poles_s)
      avar += 2.0 * t / tau *
              (1.0 - t / (2.0 * tau) * (3.0 - 4.0 * std::exp(-tau / t) + std::exp(-2.0 * tau / t)));
    adev_per_q += std::sqrt(avar) / n;
  }
  const double q2 = std::pow(b_dps / adev_per_q, 2);
  const double l = length_s;
  double var_mean = k_dps_rts * k_dps_rts * l / 3.0;
  for (double t : poles_s)
    var_mean += 2.0 * q2 * t / (l * l) *
                (l - 2.0 * t * (1.0 - std::exp(-l / t)) + t / 2.0 * (1.0 - std::exp(-2.0 * l / t)));
  const double cnt_per_dps = 20971.52;  // the ADXRS150 through the unit's ADC, datasheet nominal
  return std::sqrt(2.0 * var_mean * cnt_per_dps * cnt_per_dps + se_rows_cnt * se_rows_cnt);
}

TEST(RecordingReplay, TheRigsOwnModelAndNoiseReproduceTheRecording) {
  const fs::path dir = TempDir("same");
  const fs::path rec = RecordEveryFrame(dir);
  ReplayOptions same_noise;
  same_noise.noise_from_unit_file = true;
  const ReplaySummary s = ReplayRecording(
      rec, {rec / "truth/IMU-0001.json", rec / "truth/ADS-0001.json"}, dir / "replay", same_noise);
  EXPECT_EQ(s.replayed.size(), 2u);
  EXPECT_TRUE(s.skipped.empty());
  const hil::Recording recorded = hil::ReadRecording(rec);
  const hil::Recording replayed = hil::ReadRecording(dir / "replay");
  ASSERT_GT(recorded.imu.size(), 10000u);
  EXPECT_EQ(recorded.ads.size(), replayed.ads.size());
  const Differences d = Compare(recorded, replayed);
  std::printf(
      "same model and noise, %zu rows: max |diff| gyro %.0f, TEMP %.0f counts, T1 %.0f ticks, ps "
      "%.0f codes\n",
      recorded.imu.size(),
      d.max_gyro_cnt,
      d.max_temp_cnt,
      d.max_t1_ticks,
      d.max_ps_cnt);
  // docs/diagnose.md: reproduced to one count. The chamber column is written to 1 mK, so the
  // replayed dies differ by < 1 mK: a count on a quantiser's edge at most.
  EXPECT_LE(d.max_gyro_cnt, 1.0);
  EXPECT_LE(d.max_temp_cnt, 1.0);
  EXPECT_LE(d.max_t1_ticks, 1.0);
  EXPECT_LE(d.max_ps_cnt, 1.0);
  EXPECT_EQ(replayed.meta.extra["replay"]["of"], fs::absolute(rec).string());

  // Fresh noise and only the IMU's file: the rows differ by the noise, the means do not, and the
  // ADS is not written.
  const ReplaySummary fresh = ReplayRecording(rec, {rec / "truth/IMU-0001.json"}, dir / "fresh");
  ASSERT_EQ(fresh.skipped, std::vector<std::string>{"ADS-0001"});
  const hil::Recording other_noise = hil::ReadRecording(dir / "fresh");
  EXPECT_TRUE(other_noise.ads.empty());
  const Differences n = Compare(recorded, other_noise);
  std::printf("fresh noise: max |diff| gyro %.0f counts, mean %.2f +- %.2f counts\n",
              n.max_gyro_cnt,
              n.mean_gyro_cnt,
              n.se_mean_gyro_cnt);
  EXPECT_GT(n.max_gyro_cnt, 100.0);
  // The means differ by what two draws of the bias processes do over the run, not by a few
  // batch-means standard errors: the 500 and 5000 s processes stay near constant over these 7
  // minutes, an offset the rows' scatter does not see. Gated at the two-sided 1e-3 quantile of
  // that spread, computed from the truth's floor and walk (measured 1,962 counts against a
  // predicted standard deviation of 690: z 2.84, inside the gate's 3.29).
  const double sd_cnt = FreshNoiseMeanSdCnt(rec / "truth/IMU-0001.json",
                                            recorded.imu.back().t_s - recorded.imu.front().t_s,
                                            n.se_mean_gyro_cnt);
  std::printf(
      "fresh noise: the bias processes and rows predict a mean difference of sd %.0f "
      "counts (z %.2f)\n",
      sd_cnt,
      n.mean_gyro_cnt / sd_cnt);
  constexpr double kZ = 3.29;  // two-sided 1e-3
  EXPECT_LT(std::abs(n.mean_gyro_cnt), kZ * sd_cnt);

  // Another unit of the same profile under the recorded unit's serial and noise: its bias, scale
  // and tempco are not the recorded unit's, and its mean leaves the recording's by far more than
  // the noise explains.
  nlohmann::json other = common::ParamReader::LoadFile((rec / "truth/IMU-0001.json").string());
  other["params"] =
      sensor_sim::ImuUnitParams::Draw(
          "IMU-0001",
          7,
          sensor_sim::ModelProfileFromString(other["model_profile"].get<std::string>()))
          .ToJson();
  std::ofstream(dir / "other.json") << other.dump();
  ReplayRecording(rec, {dir / "other.json"}, dir / "other", same_noise);
  const Differences o = Compare(recorded, hil::ReadRecording(dir / "other"));
  std::printf("another unit, same noise: mean gyro difference %.1f +- %.2f counts\n",
              o.mean_gyro_cnt,
              o.se_mean_gyro_cnt);
  EXPECT_GT(std::abs(o.mean_gyro_cnt), 4.0 * o.se_mean_gyro_cnt);
  EXPECT_GT(std::abs(o.mean_gyro_cnt), kZ * sd_cnt);
  fs::remove_all(dir);
}

TEST(RecordingReplay, RefusesUnitFilesItCannotUseByName) {
  const fs::path dir = TempDir("refuse");
  const fs::path rec = RecordEveryFrame(dir);
  nlohmann::json other = common::ParamReader::LoadFile((rec / "truth/IMU-0001.json").string());
  other["params"]["serial"] = "IMU-0042";
  std::ofstream(dir / "other.json") << other.dump();
  try {
    ReplayRecording(rec, {dir / "other.json"}, dir / "out");
    FAIL() << "a unit the recording does not hold was replayed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("other.json: unit IMU-0042 is not in"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("ADS-0001, IMU-0001"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
  nlohmann::json no_seed = common::ParamReader::LoadFile((rec / "truth/IMU-0001.json").string());
  no_seed.erase("seed");
  std::ofstream(dir / "no_seed.json") << no_seed.dump();
  ReplayOptions same_noise;
  same_noise.noise_from_unit_file = true;
  EXPECT_THROW(ReplayRecording(rec, {dir / "no_seed.json"}, dir / "out", same_noise),
               std::runtime_error);
  EXPECT_THROW(ReplayRecording(rec, {rec / "truth/IMU-0001.json"}, rec),
               std::runtime_error);  // exists
  fs::remove_all(dir);
}

// A burst of rows that arrived a whole counter turn (2.56 s) late: the counter and the arrival
// times would count 256 frames too many there, but the recording's frame column (version 3) has
// the recorder's exact count, so the replay stays on the unit's own frames and reproduces every
// row to one count.
TEST(RecordingReplay, FramesComeFromTheRecordingsFrameColumn) {
  const fs::path dir = TempDir("frames");
  const fs::path rec = RecordEveryFrame(dir);
  hil::Recording recorded = hil::ReadRecording(rec);
  ASSERT_GT(recorded.imu.size(), 10000u);
  ASSERT_GE(recorded.imu.front().frame, 0);
  const size_t late_from = recorded.imu.size() / 2;
  {
    hil::RecordingWriter writer(dir / "late");
    writer.WriteMeta(recorded.meta);
    for (size_t i = 0; i < recorded.imu.size(); ++i) {
      hil::ImuRecordRow row = recorded.imu[i];
      if (i >= late_from) row.t_s += 2.56;
      writer.Append(row);
    }
    for (const hil::AdsRecordRow& row : recorded.ads) writer.Append(row);
    writer.Flush(true);
  }
  const hil::Recording late = hil::ReadRecording(dir / "late");
  ASSERT_EQ(late.imu[late_from].frame, recorded.imu[late_from].frame);
  ReplayOptions same_noise;
  same_noise.noise_from_unit_file = true;
  ReplayRecording(dir / "late", {rec / "truth/IMU-0001.json"}, dir / "replay", same_noise);
  const hil::Recording replayed = hil::ReadRecording(dir / "replay");
  ASSERT_EQ(replayed.imu.size(), late.imu.size());
  double max_gyro_cnt = 0.0;
  for (size_t i = 0; i < late.imu.size(); ++i) {
    for (size_t k = 0; k < 3; ++k) {
      max_gyro_cnt = std::max(
          max_gyro_cnt, std::abs(double(late.imu[i].gyro_cnt[k]) - replayed.imu[i].gyro_cnt[k]));
    }
  }
  EXPECT_LE(max_gyro_cnt, 1.0);
  fs::remove_all(dir);
}

// Before the chamber's first report the recording holds 0 °C and no fixture code, as the executor
// writes it: those rows are replayed at the first reported temperature, so a unit soaked at 40 °C
// does not start with a die at 0 °C.
TEST(RecordingReplay, RowsBeforeTheChambersFirstReportTakeIt) {
  const fs::path dir = TempDir("zeros");
  const auto params =
      sensor_sim::ImuUnitParams::Draw("IMU-0001", 7, sensor_sim::ModelProfile::kNominal);
  std::ofstream(dir.string() + ".json")
      << nlohmann::json{{"kind", "imu"}, {"params", params.ToJson()}}.dump();
  {
    hil::RecordingWriter writer(dir / "rec");
    writer.WriteMetaJson({{"run_id", "zeros"},
                          {"status", "complete"},
                          {"local_gravity_mps2", 9.80665},
                          {"units", {{{"kind", "imu"}, {"serial", "IMU-0001"}}}}});
    hil::ImuRecordRow row;
    row.unit = "IMU-0001";
    for (int i = 1; i <= 3000; ++i) {
      row.t_s = 0.01 * i;
      row.seq = static_cast<uint32_t>(i & 0xFF);
      row.chamber_c = i <= 500 ? 0.0 : 40.0;
      row.orientation = i <= 500 ? 0 : 31;
      writer.Append(row);
    }
    writer.Flush(true);
  }
  ReplayRecording(dir / "rec", {dir.string() + ".json"}, dir / "replay");
  const hil::Recording r = hil::ReadRecording(dir / "replay");
  ASSERT_EQ(r.imu.size(), 3000u);
  // 8.4 mV/K through 16 summed 12-bit conversions: ~110 counts per °C; a die starting at 0 °C
  // would read thousands of counts lower in the first rows.
  const double first = r.imu.front().temp_cnt[0], last = r.imu.back().temp_cnt[0];
  std::printf("TEMP gx: first row %.0f, last row %.0f counts\n", first, last);
  EXPECT_NEAR(first, last, 60.0);
  fs::remove_all(dir);
  fs::remove(dir.string() + ".json");
}

}  // namespace
}  // namespace adahrs::rig_sim
