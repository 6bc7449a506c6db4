// Generic channel CSV diagnosis (docs/diagnose.md "Generic channel CSV"): the sidecar reader's
// refusals, proofs on series written here from the physics of a thermally lagging element (known
// truth, no simulator code), and one real public recording (tests/data/pan_lsm6dsm_cold_tvac).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adahrs_build_paths.h"
#include "diagnosis/channel_diagnosis.h"
#include "diagnosis/channel_recording.h"
#include "diagnosis/diagnosis_output.h"

namespace adahrs::diagnosis {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path TempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("adahrs_channel_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void Write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

const char* kSidecar =
    R"({"format": "adahrs-channel-csv", "format_version": 1, "unit": "U1", "csv": "d.csv",
  "time": {"column": "t", "unit": "s"}, "temperature": {"column": "temp"},
  "outputs": [{"name": "y", "column": "out", "unit": "V"}]})";

std::string ErrorOf(const fs::path& sidecar) {
  try {
    ReadChannelRecording(sidecar);
  } catch (const ChannelInputError& e) {
    return e.what();
  }
  return "";
}

TEST(ChannelRecording, RefusesBadInputNamingWhere) {
  const fs::path d = TempDir("errors");
  Write(d / "d.csv", "t,temp,out,extra\n0,20,1,9\n1,20,x,9\n");
  Write(d / "s.json", kSidecar);
  EXPECT_THAT(ErrorOf(d / "s.json"),
              HasSubstr("d.csv line 3 column 3 ('out'): 'x' is not a finite number"));
  Write(d / "d.csv", "t,temp,out\n0,20,1\n1,20,2\n1,20,3\n");
  EXPECT_THAT(ErrorOf(d / "s.json"),
              HasSubstr("d.csv line 4 column 1 ('t'): time 1 s does not increase"));
  Write(d / "d.csv", "t,temperature,out\n0,20,1\n");
  EXPECT_THAT(ErrorOf(d / "s.json"), HasSubstr("d.csv line 1: no column 'temp'"));
  std::string s = kSidecar;
  Write(d / "v.json", s.replace(s.find("\"format_version\": 1"), 19, "\"format_version\": 2"));
  EXPECT_THAT(ErrorOf(d / "v.json"), HasSubstr("v.json: $.format_version: 2 is not a version"));
  s = kSidecar;
  Write(d / "k.json", s.replace(s.find("\"unit\": \"V\""), 11, "\"units\": \"V\""));
  EXPECT_THAT(ErrorOf(d / "k.json"), HasSubstr("k.json: $.outputs[0]: missing key 'unit'"));
  fs::remove_all(d);
}

TEST(ChannelRecording, MapsColumnsAndNotesTheOthers) {
  const fs::path d = TempDir("maps");
  Write(d / "d.csv", "\xEF\xBB\xBFtime (ms),temp,out,extra\r\n1000,65236,3,9\r\n1020,256,4,9\r\n");
  Write(d / "s.json",
        R"json({"format": "adahrs-channel-csv", "format_version": 1, "unit": "U1", "csv": "d.csv",
    "time": {"column": "time (ms)", "unit": "ms"}, "temperature": {"column": "temp", "int16": true, "scale": 0.00390625, "offset": 25},
    "outputs": [{"name": "y", "column": "out", "unit": "dps", "scale": 0.5}]})json");
  const ChannelRecording r = ReadChannelRecording(d / "s.json");
  ASSERT_EQ(r.t_s.size(), 2u);
  EXPECT_DOUBLE_EQ(r.t_s[1], 1.02);
  EXPECT_DOUBLE_EQ(r.temp_c[0], 25.0 - 300.0 / 256.0);  // 65236 is -300 as a signed 16-bit count
  EXPECT_DOUBLE_EQ(r.temp_c[1], 26.0);
  EXPECT_DOUBLE_EQ(r.outputs[0].values[1], 2.0);
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_THAT(r.notes[0], HasSubstr("column 'extra' ignored"));
  EXPECT_EQ(r.sha256.size(), 64u);
  fs::remove_all(d);
}

// A sensor whose element follows the chamber through a first-order lag of `tau_s` while the
// recording's thermometer reads the chamber: y = 0.03 (T_e - 25) + 2e-4 (T_e - 25)^2 + white noise
// of 0.01 per row at 10 Hz, plus `half_loop` times the sense of the last change. Profile 25 -> 5
// -> 45 -> 25 degC at 0.5 degC/min with 20 min soaks.
fs::path WriteLagging(const std::string& name, uint64_t seed, double tau_s, double half_loop) {
  const fs::path d = TempDir(name);
  std::ofstream csv(d / "d.csv");
  csv << "t,temp,out\n";
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.01);
  const double rate = 0.5 / 60.0, soak = 1200.0;
  const double legs[][2] = {{25, 5}, {5, 45}, {45, 25}};
  double t = 0.0, te = 25.0, sense = 0.0;
  auto emit = [&](double temp) {
    for (int k = 0; k < 10; ++k) {  // 1 s of rows; the element integrates the lag
      te += (temp - te) * (tau_s > 0 ? 0.1 / tau_s : 1.0);
      const double x = te - 25.0;
      csv << fmt::format("{:.1f},{:.4f},{:.6f}\n",
                         t,
                         temp,
                         0.03 * x + 2e-4 * x * x + half_loop * sense + noise(rng));
      t += 0.1;
    }
  };
  for (int s = 0; s < soak; ++s) emit(25.0);
  for (const auto& leg : legs) {
    const double dir = leg[1] > leg[0] ? 1.0 : -1.0;
    sense = dir;
    for (double temp = leg[0]; dir * (leg[1] - temp) > 0; temp += dir * rate) emit(temp);
    for (int s = 0; s < soak; ++s) emit(leg[1]);
  }
  Write(d / "s.json", kSidecar);
  return d / "s.json";
}

TEST(ChannelDiagnosis, FindsThermalLagConfoundedWithTheBiasPolynomial) {
  int found = 0, within = 0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    const fs::path s = WriteLagging("lag", seed, 60.0, 0.0);
    const UnitDiagnosis d = DiagnoseChannels(ReadChannelRecording(s));
    for (const Finding& f : d.findings) {
      std::printf("seed %d: %s\n", static_cast<int>(seed), f.words.c_str());
      if (f.effect != "thermal_lag") continue;
      ++found;
      if (std::abs(f.components[0].magnitude - 60.0) <= 3.0 * f.components[0].standard_error)
        ++within;
      EXPECT_LT(f.held_out_rms_after, f.held_out_rms_before);
    }
    EXPECT_EQ(d.findings.size(), 1u);
  }
  EXPECT_EQ(found, 10);
  EXPECT_GE(within, 9);
}

TEST(ChannelDiagnosis, FindsThermalHysteresisAndNothingOnCleanSeries) {
  int clean_with_findings = 0;
  for (uint64_t seed = 20; seed < 40; ++seed) {
    const UnitDiagnosis d =
        DiagnoseChannels(ReadChannelRecording(WriteLagging("clean", seed, 0.0, 0.0)));
    for (const Finding& f : d.findings)
      std::printf("clean seed %d: %s\n", static_cast<int>(seed), f.words.c_str());
    if (!d.findings.empty() || !d.unexplained.empty()) ++clean_with_findings;
  }
  EXPECT_LE(clean_with_findings, 1);
  const UnitDiagnosis d =
      DiagnoseChannels(ReadChannelRecording(WriteLagging("hyst", 41, 0.0, 0.004)));
  ASSERT_EQ(d.findings.size(), 1u);
  EXPECT_EQ(d.findings[0].effect, "thermal_hysteresis");
  EXPECT_NEAR(d.findings[0].components[0].magnitude,
              0.004,
              3.0 * d.findings[0].components[0].standard_error);
}

// The real recording: read through its sidecar, diagnosed without error, cooling only, so thermal
// hysteresis is not excited; whatever it reports improves the held-out fit.
TEST(ChannelDiagnosis, RealPublicRecordingOfAnLsm6dsmCoolingInAChamber) {
  const fs::path sidecar =
      fs::path(ADAHRS_SOURCE_DIR) / "tests/data/pan_lsm6dsm_cold_tvac/tvc_2020-03-07.json";
  const DiagnosisRun run = DiagnoseChannelFiles({sidecar});
  ASSERT_EQ(run.units.size(), 1u);
  const UnitDiagnosis& d = run.units[0];
  EXPECT_EQ(run.recordings[0].sha256,
            "8ad84a540e91a690b1711a00472e034d6b0a8fdafee635a724191f77eb7c3327");
  EXPECT_EQ(d.rows, 6250);
  EXPECT_EQ(d.segments, 25);
  EXPECT_NEAR(d.temp_span_c, 8.3, 0.2);
  for (const Finding& f : d.findings) {
    std::printf("finding: %s (held-out %.4g -> %.4g %s)\n",
                f.words.c_str(),
                f.held_out_rms_before,
                f.held_out_rms_after,
                f.rms_unit.c_str());
    EXPECT_LT(f.held_out_rms_after, f.held_out_rms_before);
  }
  for (const Unexplained& u : d.unexplained)
    std::printf(
        "unexplained: %s %s: %s\n", u.channel.c_str(), u.where.c_str(), u.description.c_str());
  for (const std::string& n : d.notes) std::printf("note: %s\n", n.c_str());
  for (const ChannelFitSummary& c : d.channels) {
    std::printf("%s: held-out %.4g -> %.4g %s, white %.3g\n",
                c.channel.c_str(),
                c.held_out_rms_baseline,
                c.held_out_rms_final,
                c.unit.c_str(),
                c.white_noise_rms);
  }
  for (const DetectionLimit& l : d.detection_limits) {
    for (const FindingComponent& c : l.limits) {
      std::printf("limit: %s %s: %s %.3g %s\n",
                  l.effect.c_str(),
                  l.channel.c_str(),
                  c.name.c_str(),
                  c.magnitude,
                  c.unit.c_str());
    }
    if (l.effect == "thermal_hysteresis") {
      EXPECT_TRUE(l.limits.empty()) << l.channel;  // cooling only
    }
  }
}

}  // namespace
}  // namespace adahrs::diagnosis
