// The hysteresis-compensated ADS strategy when the truth's hysteresis is not the calibration's
// model: 20 drawn units (every effect on) run through the shipped ads_calibration sequence under
// three truths side by side, fitted with the spans assumed (the class's nominal) and with the
// spans estimated from the recording, and evaluated through the fixed-point firmware on the true
// model under the evaluation's nine envelope histories.
//   matched:      the truth's law and spans are the calibration's (the travel law, nominal spans);
//   drawn spans:  the travel law, each bridge's spans drawn (20 +- 10 % FS, 20 +- 10 degC);
//   play law:     drawn spans under the play-operator law (sensor_sim/play_hysteresis.h), another
//                 family: finite slope at a reversal, loops that grow across the range.
// docs/calibration-strategies.md "Model-form mismatch" quotes what this prints.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "calib/ads_calibration/ads_calibration_points.h"
#include "calib/ads_calibration/tolerance_ads_strategy.h"
#include "hil/recording/recording_reader.h"
#include "proving/evaluation/ads_evaluation.h"
#include "tests/support/ads_recording_sim.h"

namespace adahrs::calib {
namespace {

namespace fs = std::filesystem;
using sensor_sim::AdsUnitParams;

enum class Truth { kMatched, kDrawnSpans, kPlayLaw };

const char* Name(Truth t) {
  return t == Truth::kMatched ? "matched" : t == Truth::kDrawnSpans ? "drawn spans" : "play law";
}

AdsUnitParams DrawTruth(Truth truth, const std::string& serial, uint64_t seed) {
  AdsUnitParams p = AdsUnitParams::Draw(serial, seed, sensor_sim::ModelProfile::kTruth);
  if (truth == Truth::kMatched) {
    const HysteresisSpans nominal = HysteresisSpans::Nominal();
    for (sensor_sim::PressureBridgeParams* b : {&p.static_bridge, &p.pitot_bridge}) {
      b->pressure_hysteresis_span_pct_fs = 100.0 * nominal.static_pressure_pa / b->full_scale_pa;
      b->thermal_hysteresis_span_c = nominal.static_temperature_c;
    }
  }
  if (truth == Truth::kPlayLaw) p.ApplyVariant(sensor_sim::TruthVariant::kPlayHysteresis);
  return p;
}

// Over the units, per span choice (assumed, estimated): failing grid points and the worst
// |error| / tolerance under the nine histories, altitude and airspeed; the estimated spans' worst
// relative error against the truth's (per bridge, pressure and thermal; meaningful under the
// travel law).
struct Column {
  int fails[2][2] = {};
  double worst[2][2] = {};
  double span_error[2][2] = {};  // [static, pitot][pressure, thermal]
  double centre_rms_pa[2] = {};  // worst over the units, estimated spans: static, impact
  int spans_at_search_edge = 0;
};

Column RunTwentyUnits(Truth truth) {
  constexpr int kUnits = 20;
  Column c;
  for (int i = 0; i < kUnits; ++i) {
    const std::string serial = "ADS-" + std::to_string(9200 + i);  // the 20-unit test's units
    const AdsUnitParams unit = DrawTruth(truth, serial, 6100 + i);
    // One directory per truth: ctest runs the three tests side by side.
    const fs::path run =
        fs::temp_directory_path() /
        ("adahrs_ads_model_form_" + std::to_string(static_cast<int>(truth)) + "_" + serial);
    fs::remove_all(run);
    testing::WriteAdsRecording(run, testing::ShippedSequencePath("ads_calibration"), unit, 40 + i);
    const std::vector<AdsCalibrationPoint> points =
        SelectAdsCalibrationPoints(hil::ReadRecording(run), serial, run.string());
    fs::remove_all(run);
    for (int k = 0; k < 2; ++k) {
      const SpanChoice choice = k == 0 ? SpanChoice::kAssumed : SpanChoice::kEstimated;
      const AdsFitResult fit =
          FitHysteresisAdsStrategy(serial, points, HysteresisSpans::Nominal(), choice);
      const proving::AdsEvaluation eval = proving::EvaluateAdsConstants(fit.constants, unit);
      int q = 0;
      for (const proving::AdsQuantityEvaluation* e : {&eval.altitude, &eval.airspeed}) {
        c.fails[k][q] += e->fail;
        for (const proving::AdsGridPoint& g : e->grid) {
          c.worst[k][q] = std::max(c.worst[k][q], g.worst_with_history / g.tolerance);
        }
        ++q;
      }
      if (choice == SpanChoice::kEstimated) {
        int r = 0;
        for (const AdsSurfaceDiagnostics* d :
             {&fit.diagnostics.altitude_ft, &fit.diagnostics.airspeed_kt}) {
          c.centre_rms_pa[r] =
              std::max(c.centre_rms_pa[r], d->hysteresis->centre_fit_residual_rms_pa);
          c.spans_at_search_edge += d->hysteresis_spans->at_search_edge ? 1 : 0;
          ++r;
        }
        for (int r = 0; r < 2; ++r) {
          const AdsSurfaceDiagnostics& surface =
              r == 0 ? fit.diagnostics.altitude_ft : fit.diagnostics.airspeed_kt;
          const HysteresisSpanDiagnostics& s = *surface.hysteresis_spans;
          const auto& b = r == 0 ? unit.static_bridge : unit.pitot_bridge;
          const double p_true = b.pressure_hysteresis_span_pct_fs / 100.0 * b.full_scale_pa;
          c.span_error[r][0] =
              std::max(c.span_error[r][0], std::abs(s.pressure_span_pa / p_true - 1.0));
          c.span_error[r][1] = std::max(
              c.span_error[r][1], std::abs(s.thermal_span_c / b.thermal_hysteresis_span_c - 1.0));
        }
      }
    }
  }
  std::printf(
      "%s: spans assumed: failing grid points altitude %d, airspeed %d; worst |error| / "
      "tolerance altitude %.2f, airspeed %.2f\n",
      Name(truth),
      c.fails[0][0],
      c.fails[0][1],
      c.worst[0][0],
      c.worst[0][1]);
  std::printf(
      "%s: spans estimated: failing grid points altitude %d, airspeed %d; worst |error| / "
      "tolerance altitude %.2f, airspeed %.2f; spans within %.1f %% (pressure) and %.1f %% "
      "(thermal) of the truth's on the static bridge, %.1f %% and %.1f %% on the pitot; "
      "centre-fit residual up to %.1f Pa "
      "(static), %.1f Pa (impact); %d of %d estimates on the search box's edge\n",
      Name(truth),
      c.fails[1][0],
      c.fails[1][1],
      c.worst[1][0],
      c.worst[1][1],
      100.0 * c.span_error[0][0],
      100.0 * c.span_error[0][1],
      100.0 * c.span_error[1][0],
      100.0 * c.span_error[1][1],
      c.centre_rms_pa[0],
      c.centre_rms_pa[1],
      c.spans_at_search_edge,
      2 * 20);
  return c;
}

TEST(AdsModelForm, MatchedTruthPassesWithTheSpansAssumedOrEstimated) {
  const Column c = RunTwentyUnits(Truth::kMatched);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(c.fails[k][0] + c.fails[k][1], 0) << k;
    EXPECT_LT(c.worst[k][0], 0.5) << k;
    EXPECT_LT(c.worst[k][1], 0.5) << k;
  }
}

TEST(AdsModelForm, DrawnSpansNeedTheSpansEstimated) {
  const Column c = RunTwentyUnits(Truth::kDrawnSpans);
  // Assumed: the nominal spans are wrong by up to half on these units, and the altitude goes
  // outside its tolerance somewhere on the envelope.
  EXPECT_GT(c.fails[0][0], 0);
  EXPECT_GT(c.worst[0][0], 1.0);
  // Estimated: inside every tolerance with half to spare, the spans close to the part's.
  EXPECT_EQ(c.fails[1][0] + c.fails[1][1], 0);
  EXPECT_LT(c.worst[1][0], 0.5);
  EXPECT_LT(c.worst[1][1], 0.5);
  // docs/calibration-strategies.md: the static bridge's spans within 2 % of the truth's on every
  // unit, the pitot's within 4 % (pressure) and 2 % (thermal).
  EXPECT_LT(c.span_error[0][0], 0.02);
  EXPECT_LT(c.span_error[0][1], 0.02);
  EXPECT_LT(c.span_error[1][0], 0.04);
  EXPECT_LT(c.span_error[1][1], 0.02);
}

// Another family: the unit's firmware runs the travel law, which cannot follow loops that grow
// across the range or leave a reversal with a finite slope. Measured (2026-11-26): the centre fit
// still explains the points to 5.0 Pa rms (matched: 1.4 Pa), but the envelope's histories end
// 4.7 (altitude) and 4.9 (airspeed) tolerances out with the spans estimated, 5.4 and 3.1 with
// them assumed; half the span estimates stop on the search box's edge. The tolerance is out of
// reach of the unit's law, whichever spans it is given: asserted so, with the residual's rise
// that gives it away on the recording.
TEST(AdsModelForm, PlayLawTruthIsOutOfReachOfTheUnitsLaw) {
  const Column c = RunTwentyUnits(Truth::kPlayLaw);
  for (int k = 0; k < 2; ++k) {
    EXPECT_GT(c.fails[k][0] + c.fails[k][1], 1000) << k;
    EXPECT_GT(std::max(c.worst[k][0], c.worst[k][1]), 2.5) << k;
  }
  EXPECT_GT(c.centre_rms_pa[0], 2.0 * 1.4);
  EXPECT_GT(c.spans_at_search_edge, 5);
}

}  // namespace
}  // namespace adahrs::calib
