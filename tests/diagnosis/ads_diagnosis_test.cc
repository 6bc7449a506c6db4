// ADS diagnosis proofs (docs/diagnose.md "ADS"): simulated units run through the shipped
// ads_calibration sequence (temperatures up and back down, sweeps alternating in direction, return
// points on the opposite branch). A unit whose truth carries pressure hysteresis the model lacks
// must have it found on both bridges and sized within the stated uncertainty; clean units must give
// no finding. The recordings come from the simulator (ads_recording_sim.h); the diagnoser
// (diagnosis/) never includes it.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "calib/ads_calibration/ads_calibration_points.h"
#include "diagnosis/ads_diagnosis.h"
#include "diagnosis/diagnosis_output.h"
#include "hil/recording/recording_reader.h"
#include "tests/support/ads_recording_sim.h"
#include "tests/support/sanitized_units.h"
#include "tests/support/statistical_gates.h"

namespace adahrs::diagnosis {
namespace {

namespace fs = std::filesystem;
using sensor_sim::AdsUnitParams;

UnitDiagnosis Diagnose(
    const AdsUnitParams& unit,
    uint64_t noise_seed,
    const std::string& sequence = calib::testing::ShippedSequencePath("ads_calibration")) {
  const fs::path run = fs::temp_directory_path() / ("adahrs_ads_diagnosis_" + unit.serial);
  fs::remove_all(run);
  calib::testing::WriteAdsRecording(run, sequence, unit, noise_seed);
  const std::vector<calib::AdsCalibrationPoint> points =
      calib::SelectAdsCalibrationPoints(hil::ReadRecording(run), unit.serial, run.string());
  fs::remove_all(run);
  return DiagnoseAds(unit.serial, points);
}

void Print(const UnitDiagnosis& d) {
  for (const Finding& f : d.findings)
    std::printf("  finding: %s (p %.2g, held-out %.4g -> %.4g Pa)\n",
                f.words.c_str(),
                f.wald_p_value,
                f.held_out_rms_before,
                f.held_out_rms_after);
  for (const Unexplained& u : d.unexplained)
    std::printf(
        "  unexplained: %s %s: %s\n", u.channel.c_str(), u.where.c_str(), u.description.c_str());
  for (const ChannelFitSummary& c : d.channels)
    std::printf("  %s held-out %.4g -> %.4g Pa\n",
                c.channel.c_str(),
                c.held_out_rms_baseline,
                c.held_out_rms_final);
}

// The truth's half loop in Pa: h (fraction of FSO, falling minus rising) / 2 of the full scale.
double HalfLoopPa(const sensor_sim::PressureBridgeParams& b) {
  return b.pressure_hysteresis_pct_fso / 100.0 / 2.0 * b.full_scale_pa;
}

// Clean units (nominal profile: what the model expresses). The diagnoser's stated rate of clean
// units with a finding is 2 % (docs/diagnose.md "Measured", over 700 units; the nominal level
// 0.001 is Bonferroni's): the gate allows the binomial count at that rate over these units at the
// suite's false-failure rate (tests/support/statistical_gates.h): 7 of 100; under the sanitizers
// 20 units (tests/support/sanitized_units.h), 3. No unexplained structure: the ADS diagnosis
// locates none (ads_diagnosis.h).
TEST(AdsDiagnosis, CleanRecordingsGiveNoFindings) {
  constexpr double kFindingRatePerUnit = 0.02;
  const int units = adahrs::testing::Units(100, 20);
  int with_findings = 0, with_unexplained = 0;
  for (int i = 0; i < units; ++i) {
    const AdsUnitParams unit = AdsUnitParams::Draw(
        "ADS-" + std::to_string(9300 + i), 6300 + i, sensor_sim::ModelProfile::kNominal);
    const UnitDiagnosis d = Diagnose(unit, 300 + i);
    if (!d.findings.empty() || !d.unexplained.empty()) {
      std::printf("%s:\n", unit.serial.c_str());
      Print(d);
    }
    with_findings += d.findings.empty() ? 0 : 1;
    with_unexplained += d.unexplained.empty() ? 0 : 1;
  }
  std::printf("clean ADS: %d of %d units with a finding, %d with unexplained structure\n",
              with_findings,
              units,
              with_unexplained);
  EXPECT_LE(with_findings, adahrs::testing::AllowedCount(units, kFindingRatePerUnit));
  EXPECT_EQ(with_unexplained, 0);
}

// Pressure hysteresis the model lacks: a single-valued surface returns one branch where the points
// went up and the other where they came down. On the static bridge (12...109 kPa, five spans of
// travel): found on every unit, half loop within 3 standard errors of the truth's on at least 9 of
// 10. On the pitot bridge (0...37 kPa, under two spans, one branch per temperature): found on at
// least 8 of 10 and within 3 SE of the truth's on all but the binomial share of those found (8 of
// 9); on both the standard errors bounded by the half loops' scatter about the truth
// (docs/diagnose.md gives the measured counts).
TEST(AdsDiagnosis, FindsPressureHysteresisFromUpAndDownSweeps) {
  int found[2] = {}, within[2] = {};
  adahrs::testing::StandardErrorBound bound[2] = {
      adahrs::testing::StandardErrorBound("static half loop"),
      adahrs::testing::StandardErrorBound("pitot half loop")};
  int pitot_span_beyond_8_pct = 0;
  for (int i = 0; i < 10; ++i) {
    AdsUnitParams unit = AdsUnitParams::Draw(
        "ADS-" + std::to_string(9400 + i), 6400 + i, sensor_sim::ModelProfile::kNominal);
    for (sensor_sim::PressureBridgeParams* b : {&unit.static_bridge, &unit.pitot_bridge})
      b->effects.pressure_hysteresis = true;
    const UnitDiagnosis d = Diagnose(unit, 400 + i);
    for (const Finding& f : d.findings) {
      if (f.effect != "pressure_hysteresis") {
        ADD_FAILURE() << unit.serial << ": " << f.words;
        continue;
      }
      const int k = f.channel == "ps" ? 0 : 1;
      const auto& b = k == 0 ? unit.static_bridge : unit.pitot_bridge;
      const double truth = HalfLoopPa(b);
      const FindingComponent& half = f.components[0];
      std::printf(
          "%s %s: half loop %.2f +- %.2f Pa, truth %.2f Pa; span %.0f +- %.0f Pa, truth %.0f Pa\n",
          unit.serial.c_str(),
          f.channel.c_str(),
          half.magnitude,
          half.standard_error,
          truth,
          f.components[1].magnitude,
          f.components[1].standard_error,
          b.pressure_hysteresis_span_pct_fs / 100.0 * b.full_scale_pa);
      ++found[k];
      if (std::abs(half.magnitude - truth) <= 3.0 * half.standard_error) ++within[k];
      bound[k].Add(half.magnitude, half.standard_error, truth);
      EXPECT_LT(f.held_out_rms_after, f.held_out_rms_before);
      // The span (docs/diagnose.md): the static bridge's within 2 % of the truth's on every unit;
      // the pitot's within 8 % on all but two. Its standard error is not leaned on: it leaves out
      // the spans' correlation and understates (docs/calibration-strategies.md).
      const FindingComponent& span = f.components[1];
      const double span_truth = b.pressure_hysteresis_span_pct_fs / 100.0 * b.full_scale_pa;
      const double span_error = std::abs(span.magnitude / span_truth - 1.0);
      if (k == 0) {
        EXPECT_LT(span_error, 0.02) << unit.serial;
      } else {
        pitot_span_beyond_8_pct += span_error > 0.08 ? 1 : 0;
      }
    }
  }
  std::printf(
      "pressure hysteresis: static bridge found on %d of 10 (%d within 3 SE), pitot on %d of 10 "
      "(%d within 3 SE)\n",
      found[0],
      within[0],
      found[1],
      within[1]);
  EXPECT_EQ(found[0], 10);
  EXPECT_GE(found[1], 8);
  for (int k = 0; k < 2; ++k) {
    EXPECT_GE(within[k], adahrs::testing::RequiredWithinThreeSe(found[k])) << k;
    bound[k].Expect(k == 0 ? 10 : 8);
  }
  EXPECT_LE(pitot_span_beyond_8_pct, 2);
}

// The shipped ads_calibration sequence cut to its first prompt and the steps at `target_c`: one
// soak, then its altitude and airspeed sweeps with their return points. Written under `dir`.
std::string OneTemperatureSequence(const fs::path& dir, double target_c) {
  std::ifstream in(calib::testing::ShippedSequencePath("ads_calibration"));
  nlohmann::json seq = nlohmann::json::parse(in);
  nlohmann::json steps = nlohmann::json::array({seq["steps"][0]});
  bool inside = false;
  for (const nlohmann::json& step : seq["steps"]) {
    if (step["kind"] == "target_temperature") {
      if (inside) break;
      inside = step["target_c"].get<double>() == target_c;
    }
    if (inside) steps.push_back(step);
  }
  seq["steps"] = steps;
  seq["name"] = "ads_calibration_one_temperature";
  fs::create_directories(dir);
  const fs::path path = dir / "ads_calibration_one_temperature.json";
  std::ofstream(path) << seq.dump(2);
  return path.string();
}

// Points at one chamber temperature (25 degC: the shipped sequence's sweeps there, 50 points):
// pressure hysteresis is still tested, with the baseline a polynomial in pressure alone; thermal
// hysteresis is stated as not testable rather than given a limit (the pitot's loop and
// nonlinearity mostly are too, by their range: its airspeeds go down once and its top points are
// extrapolation when held out; printed, not asserted). On the static bridge (five spans of travel
// down and back) the loop is found on at least 9 of 10 units and its half loop within 3 standard
// errors plus 1 % of the truth on at least 9 of those found (the 1 %: the diagnoser's loop law is
// not the simulated unit's, and one temperature averages nothing; docs/diagnose.md gives the
// measured offsets); clean units give a finding on at most 1 of 10.
TEST(AdsDiagnosis, OneTemperatureStillTestsPressureHysteresis) {
  const std::string sequence =
      OneTemperatureSequence(fs::temp_directory_path() / "adahrs_ads_one_temperature", 25.0);
  int found = 0, within = 0, clean_with_findings = 0, pitot_not_testable = 0;
  adahrs::testing::StandardErrorBound bound("static half loop, one temperature");
  for (int i = 0; i < 10; ++i) {
    AdsUnitParams unit = AdsUnitParams::Draw(
        "ADS-" + std::to_string(9600 + i), 6600 + i, sensor_sim::ModelProfile::kNominal);
    const UnitDiagnosis clean = Diagnose(unit, 600 + i, sequence);
    if (!clean.findings.empty()) {
      ++clean_with_findings;
      std::printf("clean %s:\n", unit.serial.c_str());
      Print(clean);
    }
    for (sensor_sim::PressureBridgeParams* b : {&unit.static_bridge, &unit.pitot_bridge})
      b->effects.pressure_hysteresis = true;
    const UnitDiagnosis d = Diagnose(unit, 700 + i, sequence);
    for (const DetectionLimit& l : d.detection_limits) {
      if (l.channel == "pt" && l.effect != "thermal_hysteresis")
        pitot_not_testable += l.limits.empty() ? 1 : 0;
      if (l.effect != "thermal_hysteresis") continue;
      EXPECT_TRUE(l.limits.empty()) << l.effect << " " << l.channel;
      EXPECT_EQ(l.note.rfind("not testable here: ", 0), 0u) << l.note;
    }
    for (const Finding& f : d.findings) {
      EXPECT_NE(f.effect, "thermal_hysteresis") << f.words;
      if (f.effect != "pressure_hysteresis" || f.channel != "ps") continue;
      const double truth = HalfLoopPa(unit.static_bridge);
      const FindingComponent& half = f.components[0];
      std::printf(
          "%s ps: half loop %.2f +- %.2f Pa, truth %.2f Pa; span %.0f +- %.0f Pa, truth %.0f Pa\n",
          unit.serial.c_str(),
          half.magnitude,
          half.standard_error,
          truth,
          f.components[1].magnitude,
          f.components[1].standard_error,
          unit.static_bridge.pressure_hysteresis_span_pct_fs / 100.0 *
              unit.static_bridge.full_scale_pa);
      ++found;
      if (std::abs(half.magnitude - truth) <= 3.0 * half.standard_error + 0.01 * truth) ++within;
      bound.Add(half.magnitude, half.standard_error, truth);
      EXPECT_LT(f.held_out_rms_after, f.held_out_rms_before);
    }
    if (i == 0) {
      Print(d);
      for (const DetectionLimit& l : d.detection_limits)
        std::printf(
            "  limit %s %s: %s\n",
            l.effect.c_str(),
            l.channel.c_str(),
            l.limits.empty()
                ? l.note.c_str()
                : fmt::format("{:.3g} {}", l.limits[0].magnitude, l.limits[0].unit).c_str());
      for (const std::string& n : d.notes) std::printf("  note: %s\n", n.c_str());
    }
  }
  std::printf(
      "one temperature: static pressure hysteresis found on %d of 10 (%d within 3 SE + 1 %%); "
      "clean units with a finding: %d of 10; pitot loop and nonlinearity not testable on %d of "
      "20\n",
      found,
      within,
      clean_with_findings,
      pitot_not_testable);
  EXPECT_GE(found, 9);
  EXPECT_GE(within, adahrs::testing::RequiredWithinThreeSe(found));
  bound.Expect(9);
  EXPECT_LE(clean_with_findings, 1);
}

// Two or three chamber temperatures cannot choose the baseline's degree in temperature by held-out
// interior temperatures: refused naming the unit and the count.
TEST(AdsDiagnosis, TwoTemperaturesAreRefusedNamingTheCount) {
  std::vector<calib::AdsCalibrationPoint> points;
  const fs::path dir = fs::temp_directory_path() / "adahrs_ads_two_temperatures";
  const AdsUnitParams unit =
      AdsUnitParams::Draw("ADS-9700", 6700, sensor_sim::ModelProfile::kNominal);
  for (double t : {25.0, 65.0}) {
    const fs::path run = dir / std::to_string(static_cast<int>(t));
    fs::remove_all(run);
    calib::testing::WriteAdsRecording(run, OneTemperatureSequence(dir, t), unit, 800);
    for (const calib::AdsCalibrationPoint& p :
         calib::SelectAdsCalibrationPoints(hil::ReadRecording(run), unit.serial, run.string()))
      points.push_back(p);
  }
  fs::remove_all(dir);
  try {
    DiagnoseAds(unit.serial, points);
    ADD_FAILURE() << "two temperatures were diagnosed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("ADS-9700: the points visit 2 chamber temperatures"),
              std::string::npos)
        << e.what();
  }
}

// Appends a column the recording format does not know to every line of `csv`.
void AppendForeignColumn(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line, text;
  for (int n = 0; std::getline(in, line); ++n)
    text += line + (n == 0 ? ",humidity_pct" : ",41.5") + "\n";
  in.close();
  std::ofstream(csv) << text;
}

// `adahrs diagnose` on an ADS run directory: the unit is found by its kind in meta.json and written
// under the documented contract, both bridges summarised; a column the format does not know is
// ignored with a note.
TEST(AdsDiagnosis, DiagnoseRunsReadsAnAdsRunDirectory) {
  AdsUnitParams unit = AdsUnitParams::Draw("ADS-9500", 6500, sensor_sim::ModelProfile::kNominal);
  unit.static_bridge.effects.pressure_hysteresis = true;
  const fs::path run = fs::temp_directory_path() / "adahrs_ads_diagnosis_runs";
  fs::remove_all(run);
  calib::testing::WriteAdsRecording(
      run, calib::testing::ShippedSequencePath("ads_calibration"), unit, 500);
  AppendForeignColumn(run / "ads.csv");
  const DiagnosisRun d = DiagnoseRuns({run}, std::nullopt);
  EXPECT_THROW(DiagnoseRuns({run}, std::string("ADS-9999")), calib::ImuInputError);
  fs::remove_all(run);
  ASSERT_EQ(d.units.size(), 1u);
  EXPECT_EQ(d.units[0].serial, "ADS-9500");
  ASSERT_EQ(d.units[0].channels.size(), 2u);
  const nlohmann::json j = d.ToJson();
  EXPECT_EQ(j["format"], "adahrs-diagnosis");
  ASSERT_EQ(j["recording"].size(), 1u);
  EXPECT_EQ(j["recording"][0]["sha256"].get<std::string>().size(), 64u);
  ASSERT_GE(j["findings"].size(), 1u);
  EXPECT_EQ(j["findings"][0]["effect"], "pressure_hysteresis");
  EXPECT_EQ(j["findings"][0]["channels"], nlohmann::json::array({"ps"}));
  EXPECT_EQ(j["detection_limits"].size(), 6u);
  ASSERT_EQ(j["notes"].size(), 1u);
  EXPECT_NE(j["notes"][0].get<std::string>().find("'humidity_pct' is not in the recording format"),
            std::string::npos);
  EXPECT_NE(DiagnosisHtml(d).find("calibration point"), std::string::npos);
  EXPECT_NE(DiagnosisHtml(d).find("humidity_pct"), std::string::npos);
}

}  // namespace
}  // namespace adahrs::diagnosis
