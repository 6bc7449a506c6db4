// Generic channel CSV diagnosis (docs/diagnose.md "Generic channel CSV"): the sidecar reader's
// refusals, proofs on series written here from the physics of a thermally lagging element (known
// truth, no simulator code), and one real public recording (tests/data/pan_lsm6dsm_cold_tvac).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <string>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adahrs_build_paths.h"
#include "diagnosis/channel_diagnosis.h"
#include "diagnosis/channel_recording.h"
#include "diagnosis/diagnosis_output.h"
#include "diagnosis/plausible_range.h"
#include "tests/support/statistical_gates.h"

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

// The lag found on every series, within 3 standard errors of the truth's 60 s on all but the
// binomial share, those errors bounded by the estimates' scatter about 60 s.
TEST(ChannelDiagnosis, FindsThermalLagConfoundedWithTheBiasPolynomial) {
  int found = 0, within = 0;
  adahrs::testing::StandardErrorBound bound("thermal lag");
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    const fs::path s = WriteLagging("lag", seed, 60.0, 0.0);
    const UnitDiagnosis d = DiagnoseChannels(ReadChannelRecording(s));
    for (const Finding& f : d.findings) {
      std::printf("seed %d: %s\n", static_cast<int>(seed), f.words.c_str());
      if (f.effect != "thermal_lag") continue;
      ++found;
      if (std::abs(f.components[0].magnitude - 60.0) <= 3.0 * f.components[0].standard_error)
        ++within;
      bound.Add(f.components[0].magnitude, f.components[0].standard_error, 60.0);
      EXPECT_LT(f.held_out_rms_after, f.held_out_rms_before);
    }
    EXPECT_EQ(d.findings.size(), 1u);
  }
  std::printf("thermal lag: found on %d of 10, %d within 3 SE\n", found, within);
  EXPECT_EQ(found, 10);
  EXPECT_GE(within, adahrs::testing::RequiredWithinThreeSe(found));
  bound.Expect(10);
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
  // The half loop of 0.004 on 10 series: found alone on each, within 3 standard errors on all but
  // the binomial share, those errors bounded by the estimates' scatter about 0.004.
  int within = 0;
  adahrs::testing::StandardErrorBound bound("thermal hysteresis");
  for (uint64_t seed = 41; seed <= 50; ++seed) {
    const UnitDiagnosis d =
        DiagnoseChannels(ReadChannelRecording(WriteLagging("hyst", seed, 0.0, 0.004)));
    ASSERT_EQ(d.findings.size(), 1u) << "seed " << seed;
    EXPECT_EQ(d.findings[0].effect, "thermal_hysteresis");
    const FindingComponent& h = d.findings[0].components[0];
    within += std::abs(h.magnitude - 0.004) <= 3.0 * h.standard_error ? 1 : 0;
    bound.Add(h.magnitude, h.standard_error, 0.004);
  }
  std::printf("thermal hysteresis: %d of 10 within 3 SE\n", within);
  EXPECT_GE(within, adahrs::testing::RequiredWithinThreeSe(10));
  bound.Expect(10);
}

// A limit beyond what the effect can physically be is "not testable here", stated with the range
// (physics.md: a board in a housing lags by minutes, self-heating is a few degC).
TEST(PlausibleRange, LimitsBeyondPhysicsAreNotTestable) {
  EXPECT_EQ(NotTestableReason({{"delay", 660.0, 100.0, "s"}}, 7320.0), "");
  EXPECT_THAT(NotTestableReason({{"delay", 1.2e5, 3e4, "s"}}, 7320.0),
              HasSubstr("not testable here: the smallest delay"));
  EXPECT_THAT(NotTestableReason({{"delay", 2000.0, 500.0, "s"}}, 1500.0),
              HasSubstr("at most 1500 s"));  // longer than the recording
  EXPECT_EQ(NotTestableReason({{"initial_excess", 0.76, 0.2, "degC"}}, 7320.0), "");
  EXPECT_THAT(NotTestableReason({{"initial_excess", 3e3, 1e3, "degC"}}, 7320.0),
              HasSubstr("at most 20 degC"));
  EXPECT_THAT(
      NotTestableReason({{"tc1", 10.0, 1.0, "ppm/degC"}, {"tc2", 2e5, 1.0, "ppm/degC^2"}}, 7320.0),
      HasSubstr("smallest tc2"));
  EXPECT_EQ(NotTestableReason({{"half_loop", 1e9, 1.0, "dps"}}, 7320.0), "");  // no stated range
}

// `minutes` of 10 Hz rows, white noise 0.01 per row, no temperature coefficient, no effect:
// temp_c(t) gives the thermometer. `shift` is added from `shift_from_s` on (an orientation change
// between two stretches of the run).
fs::path WriteFlat(const std::string& name,
                   uint64_t seed,
                   double minutes,
                   const std::function<double(double)>& temp_c,
                   double slope_per_c = 0.0,
                   double shift = 0.0,
                   double shift_from_s = 0.0) {
  const fs::path d = TempDir(name);
  std::ofstream csv(d / "d.csv");
  csv << "t,temp,out\n";
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int i = 0; i < static_cast<int>(minutes * 600); ++i) {
    const double t = 0.1 * i, temp = temp_c(t);
    const double y = slope_per_c * (temp - 25.0) + (t >= shift_from_s ? shift : 0.0) + noise(rng);
    csv << fmt::format("{:.1f},{:.4f},{:.6f}\n", t, temp, y);
  }
  Write(d / "s.json", kSidecar);
  return d / "s.json";
}

bool LagOrWarmUp(const DetectionLimit& l) {
  return l.effect == "thermal_lag" || l.effect.rfind("self_heating_warm_up", 0) == 0;
}

// Zero temperature change: a lag or a warm-up between element and thermometer leaves nothing in
// the output, so no detection limit is printed for them (the rank rule or the plausible range
// says why), and nothing is found.
TEST(ChannelDiagnosis, NoTemperatureChangeMeansNotTestableNotAnAbsurdLimit) {
  // A chamber holding 25 degC, its probe read to 0.01 degC with 0.02 degC of noise.
  std::mt19937_64 probe(7);
  std::normal_distribution<double> probe_noise(0.0, 0.02);
  const auto held = [&](double) { return 25.0 + std::round(probe_noise(probe) * 100.0) / 100.0; };
  const auto exactly = [](double) { return 25.0; };
  for (const auto& temp :
       {std::function<double(double)>(held), std::function<double(double)>(exactly)}) {
    const UnitDiagnosis d =
        DiagnoseChannels(ReadChannelRecording(WriteFlat("flat", 3, 60.0, temp)));
    EXPECT_TRUE(d.findings.empty());
    for (const DetectionLimit& l : d.detection_limits) {
      std::printf("%s: %s\n", l.effect.c_str(), l.limits.empty() ? l.note.c_str() : "a limit");
      if (!LagOrWarmUp(l) && l.effect != "thermal_hysteresis") continue;
      EXPECT_TRUE(l.limits.empty()) << l.effect;
      EXPECT_FALSE(l.note.empty()) << l.effect;
    }
  }
}

// A temperature span but an output that does not depend on it: the bias slope is about zero, and
// so is a lag's or warm-up's leverage. No printed limit lies beyond the plausible range; the
// thermal hysteresis (both senses visited) keeps a finite limit.
TEST(ChannelDiagnosis, ZeroBiasSlopeLeavesNoAbsurdLimit) {
  const auto cycle = [](double t) {  // 25 -> 15 -> 35 -> 25 degC at 1 degC/min
    const double m = t / 60.0;
    if (m < 10) return 25.0 - m;
    if (m < 30) return 15.0 + (m - 10);
    return std::max(25.0, 35.0 - (m - 30));
  };
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    const UnitDiagnosis d =
        DiagnoseChannels(ReadChannelRecording(WriteFlat("zero_slope", seed, 60.0, cycle)));
    EXPECT_TRUE(d.findings.empty());
    bool hysteresis_limit = false;
    for (const DetectionLimit& l : d.detection_limits) {
      for (const FindingComponent& c : l.limits)
        EXPECT_LE(c.magnitude, PlausibleMagnitude(c.name, c.unit, 3600.0)) << l.effect;
      if (LagOrWarmUp(l)) {
        EXPECT_TRUE(l.limits.empty())
            << l.effect << " " << seed << " " << (l.limits.empty() ? 0.0 : l.limits[0].magnitude);
      }
      hysteresis_limit |= l.effect == "thermal_hysteresis" && !l.limits.empty();
    }
    EXPECT_TRUE(hysteresis_limit);
  }
}

// Two plateaus, 25 and 35 degC (15 min each, a 10 min ramp between), a bias of 0.01 per degC and,
// with `shift`, an offset added halfway through the second plateau (the unit turned over between
// two stretches of one soak): a bias polynomial in temperature cannot follow it, so the held-out
// error stands far above the white noise and must be reported, never "no missing physics".
fs::path WritePlateaus(const std::string& name, uint64_t seed, double shift) {
  const auto two = [](double t) {
    const double m = t / 60.0;
    return m < 15 ? 25.0 : std::min(35.0, 25.0 + (m - 15));
  };
  return WriteFlat(name, seed, 40.0, two, 0.01, shift, 32.5 * 60.0);
}

TEST(ChannelDiagnosis, HeldOutErrorFarAboveTheNoiseIsUnexplainedNeverClean) {
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    const DiagnosisRun run =
        DiagnoseChannelFiles({WritePlateaus("shifted", seed, 0.1)});  // 31 x the cell noise
    const UnitDiagnosis& d = run.units[0];
    for (const Unexplained& u : d.unexplained)
      std::printf("seed %d unexplained: %s: %s\n",
                  static_cast<int>(seed),
                  u.where.c_str(),
                  u.description.c_str());
    ASSERT_EQ(d.channels.size(), 1u);
    EXPECT_GE(d.channels[0].held_out_rms_final, 3.0 * d.channels[0].white_noise_rms);
    EXPECT_FALSE(d.NoMissingPhysics());
    const nlohmann::json j = run.ToJson();
    EXPECT_NE(j["units"][0]["verdict"], "no missing physics found");
    bool excess = false;
    for (const nlohmann::json& u : j["unexplained"]) {
      const std::string where = u["where"];
      if (u["description"].get<std::string>().find("held-out RMS") == std::string::npos) continue;
      excess = true;
      EXPECT_EQ(u["channel"], "y");
      // The segments named first lie on the second plateau (t >= 25 min, 35 degC).
      EXPECT_THAT(where, HasSubstr("35.0 degC"));
      EXPECT_THAT(where.substr(0, where.find(';')), HasSubstr("35.0 degC"));
    }
    EXPECT_TRUE(excess);
  }
}

TEST(ChannelDiagnosis, TheSamePlateausWithoutTheShiftComeOutClean) {
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    const DiagnosisRun run = DiagnoseChannelFiles({WritePlateaus("unshifted", seed, 0.0)});
    const UnitDiagnosis& d = run.units[0];
    for (const Unexplained& u : d.unexplained)
      std::printf("unexplained: %s\n", u.description.c_str());
    EXPECT_LT(d.channels[0].held_out_rms_final, 3.0 * d.channels[0].white_noise_rms);
    EXPECT_TRUE(d.NoMissingPhysics());
    EXPECT_EQ(run.ToJson()["units"][0]["verdict"], "no missing physics found");
  }
}

// A logger's file: a banner, no time column (rows at a stated 10 Hz), two garbled rows, segments
// cut every 60 s. Time counts every data row, the skipped ones too (a garbled row still took its
// sample slot).
TEST(ChannelRecording, ReadsARealLoggersFile) {
  const fs::path d = TempDir("logger");
  std::ofstream csv(d / "d.csv");
  csv << "LOGGER v2.1 serial 0042\nstarted 2026-01-01 10:00\n\ntemp,out\n";
  const int rows = 10 * 600;  // 10 min
  for (int i = 0; i < rows; ++i) {
    if (i == 1234) {
      csv << "21.5,1.0e\x01\n";  // a garbled cell
    } else if (i == 4000) {
      csv << "21.5\n";  // a truncated row
    } else {
      csv << fmt::format("{:.3f},{:.5f}\n", 20.0 + i * 1e-3, 0.01 * std::sin(0.01 * i));
    }
  }
  csv.close();
  Write(d / "s.json",
        R"({"format": "adahrs-channel-csv", "format_version": 1, "device": "logger 0042",
  "csv": "d.csv", "skip_lines": 3, "segment_s": 60, "time": {"rate_hz": 10},
  "temperature": {"column": "temp"}, "outputs": [{"name": "y", "column": "out", "unit": "V"}]})");
  const ChannelRecording r = ReadChannelRecording(d / "s.json");
  EXPECT_EQ(r.unit, "logger 0042");
  EXPECT_EQ(r.skipped_rows, 2);
  ASSERT_EQ(r.t_s.size(), static_cast<size_t>(rows - 2));
  EXPECT_DOUBLE_EQ(r.t_s[1233], 123.3);
  EXPECT_DOUBLE_EQ(r.t_s[1234], 123.5);  // row 1234 skipped: its slot stays empty
  EXPECT_DOUBLE_EQ(r.temp_c[1234], 20.0 + 1235e-3);
  EXPECT_DOUBLE_EQ(r.segment_s, 60.0);
  std::string notes;
  for (const std::string& n : r.notes) notes += n + "\n";
  EXPECT_THAT(notes, HasSubstr("2 of 6000 rows do not parse and were skipped"));
  // Line 5 is the first data row: row 1234 is line 1239.
  EXPECT_THAT(notes, HasSubstr("d.csv line 1239 column 2 ('out')"));
  EXPECT_THAT(notes, HasSubstr("no time column"));
  const UnitDiagnosis u = DiagnoseChannels(r);
  EXPECT_EQ(u.segments, 10);  // 600 s cut every 60 s
  fs::remove_all(d);
}

TEST(ChannelRecording, RefusesAFileWhoseRowsMostlyDoNotParse) {
  const fs::path d = TempDir("garbled");
  Write(d / "d.csv", "t,temp,out\n0,20,1\n1,20,?\n2,20,?\n3,20,4\n4,x,5\n");
  Write(d / "s.json", kSidecar);
  EXPECT_THAT(ErrorOf(d / "s.json"),
              HasSubstr("3 of 5 rows do not parse (the sidecar's columns may not be this "
                        "file's); the first: "));
  fs::remove_all(d);
}

// Too short for three 120 s segments: the refusal says the cut is the reason and which option
// changes it; with segment_s 60 the same rows are diagnosed.
TEST(ChannelDiagnosis, ShortRunRefusalNamesTheSegmentCut) {
  const fs::path s = WriteFlat(
      "short", 5, 4.0, [](double t) { return 20.0 + t / 60.0; }, 0.01);
  std::string why;
  try {
    DiagnoseChannels(ReadChannelRecording(s));
  } catch (const ChannelInputError& e) {
    why = e.what();
  }
  EXPECT_THAT(why, HasSubstr("2 segment(s)"));
  EXPECT_THAT(why, HasSubstr("segments are cut every 120 s (sidecar 'segment_s')"));
  std::string sidecar = kSidecar;
  Write(s, sidecar.insert(sidecar.size() - 1, R"(, "segment_s": 60)"));
  const UnitDiagnosis d = DiagnoseChannels(ReadChannelRecording(s));
  EXPECT_EQ(d.segments, 4);
}

// The bias slope against temperature, the number an engineer wants first, with its standard
// error: the plateaus' 0.01 per degC within 3 of them.
TEST(ChannelDiagnosis, ReportsTheBiasSlopeAgainstTemperature) {
  const DiagnosisRun run = DiagnoseChannelFiles({WritePlateaus("slope", 9, 0.0)});
  const ChannelFitSummary& c = run.units[0].channels[0];
  ASSERT_TRUE(c.bias_slope_per_c.has_value());
  std::printf("slope %.6g ± %.2g\n", *c.bias_slope_per_c, *c.bias_slope_se_per_c);
  EXPECT_GT(*c.bias_slope_se_per_c, 0.0);
  EXPECT_LT(*c.bias_slope_se_per_c, 1e-3);
  EXPECT_NEAR(*c.bias_slope_per_c, 0.01, 3.0 * *c.bias_slope_se_per_c);
  const nlohmann::json j = run.ToJson()["units"][0]["channels"][0]["bias_slope_per_degc"];
  EXPECT_EQ(j["unit"], "V/degC");
  EXPECT_DOUBLE_EQ(j["value"].get<double>(), *c.bias_slope_per_c);
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
  // docs/diagnose.md: no missing physics; a thermal lag would have been found above 660 s (gx)
  // and 722 s (gy), a warm-up above 0.76 and 0.85 degC (the smallest over the warm-up time
  // constants tried). The file is fixed, so these are what the diagnosis gives it, within 1 %: the
  // docs' rounding plus room for another compiler's libm; a limit further off is a changed
  // diagnosis that the docs must follow.
  EXPECT_TRUE(d.NoMissingPhysics()) << d.Verdict();
  EXPECT_TRUE(d.findings.empty());
  EXPECT_TRUE(d.unexplained.empty());
  const auto smallest_limit = [&](const std::string& effect, const std::string& channel) {
    double smallest = std::numeric_limits<double>::infinity();
    for (const DetectionLimit& l : d.detection_limits) {
      if (l.effect.rfind(effect, 0) != 0 || l.channel != channel) continue;
      EXPECT_EQ(l.limits.size(), 1u) << l.effect << " " << channel << ": " << l.note;
      for (const FindingComponent& c : l.limits) smallest = std::min(smallest, c.magnitude);
    }
    return smallest;
  };
  EXPECT_NEAR(smallest_limit("thermal_lag", "gx"), 660.0, 6.6);
  EXPECT_NEAR(smallest_limit("thermal_lag", "gy"), 722.0, 7.2);
  EXPECT_NEAR(smallest_limit("self_heating_warm_up", "gx"), 0.76, 0.0076);
  EXPECT_NEAR(smallest_limit("self_heating_warm_up", "gy"), 0.85, 0.0085);
}

}  // namespace
}  // namespace adahrs::diagnosis
