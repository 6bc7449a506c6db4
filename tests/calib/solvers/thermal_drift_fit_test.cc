// Constructed-truth tests of the reference thermal model: recovery of a known quadratic, equal
// weight per temperature band, up/down hysteresis, and the refusal of too few temperatures.
#include "calib/solvers/thermal_drift_fit.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/random.h"

namespace adahrs::calib {
namespace {

using ::testing::HasSubstr;

// A gyro-like channel: counts vs temperature counts 27,000..38,000 (-20..+65 degC at ~110 counts
// per degC around 32,768 at 25 degC).
constexpr double kK0 = -1.2e6, kK1 = 770.0, kK2 = -0.0089;  // magnitudes of Table 13's gx
double Quadratic(double t) { return kK0 + kK1 * t + kK2 * t * t; }

std::vector<ThermalSample> Ramp(double t0,
                                double t1,
                                int n,
                                ThermalSegment segment,
                                common::Rng& rng,
                                double noise,
                                double (*f)(double)) {
  std::vector<ThermalSample> out;
  for (int i = 0; i < n; ++i) {
    const double t = t0 + (t1 - t0) * i / (n - 1);
    out.push_back({t, f(t) + noise * rng.Normal(), segment});
  }
  return out;
}

TEST(ThermalDriftFit, RecoversQuadraticWithinStandardErrors) {
  common::Rng rng(31);
  auto samples = Ramp(27000, 38000, 3000, ThermalSegment::kUpRamp, rng, 8000.0, Quadratic);
  const auto down = Ramp(38000, 27000, 3000, ThermalSegment::kDownRamp, rng, 8000.0, Quadratic);
  samples.insert(samples.end(), down.begin(), down.end());
  const ThermalDriftResult r = FitThermalDrift("gx", samples);
  // Gaussian noise, correct model: each estimate within 4 standard errors (p < 1e-4 per check).
  // The raw coefficients are strongly correlated, so check the curve at three temperatures too.
  for (double t : {27500.0, 32768.0, 37500.0}) {
    EXPECT_NEAR(r.all.Drift(t), Quadratic(t), 4.0 * r.all.DriftStandardError(t)) << t;
  }
  EXPECT_NEAR(r.all.k[2], kK2, 4.0 * r.all.k_se[2]);
  // se of the curve ~ sigma * sqrt(3 / n) for a quadratic over a uniform range: 8000 * sqrt(3 /
  // 6000) ~ 180 counts at the middle; check the order (factor 2) so a scale error shows.
  EXPECT_GT(r.all.DriftStandardError(32768), 90.0);
  EXPECT_LT(r.all.DriftStandardError(32768), 360.0);
  ASSERT_TRUE(r.up && r.down) << r.ramp_note;
  // No hysteresis in the data: the up/down gap is noise, within 4 se of each curve's difference.
  EXPECT_LT(r.hysteresis,
            4.0 * std::hypot(r.up->DriftStandardError(r.hysteresis_at_temp_cnt),
                             r.down->DriftStandardError(r.hysteresis_at_temp_cnt)));
}

double Cubic(double t) {
  const double u = (t - 32768.0) / 5500.0;
  return 1000.0 * u * u * u;
}

// Equal weight per band: a cubic (model error for a quadratic) sampled on a uniform ramp plus a
// long soak at the hot end. Unweighted, the soak drags the quadratic towards itself; band-weighted
// the fit equals the fit of the ramp alone (the soak adds one band among ~100, so the difference is
// ~1 % of the fit's model error, while the unweighted fit moves by a large fraction of it).
TEST(ThermalDriftFit, EveryTemperatureBandWeighsTheSame) {
  common::Rng rng(32);
  const auto ramp = Ramp(27000, 38000, 2000, ThermalSegment::kUpRamp, rng, 0.0, Cubic);
  auto with_soak = ramp;
  const auto soak = Ramp(37950, 38000, 20000, ThermalSegment::kSoak, rng, 0.0, Cubic);
  with_soak.insert(with_soak.end(), soak.begin(), soak.end());

  const ThermalPolynomial reference = FitThermalDrift("az1", ramp).all;
  const ThermalPolynomial balanced = FitThermalDrift("az1", with_soak).all;
  ThermalFitOptions one_band;
  one_band.band_width_cnt = 1e6;  // every sample in one band: the plain unweighted fit
  one_band.min_bands = 1;
  const ThermalPolynomial plain = FitThermalDrift("az1", with_soak, one_band).all;
  const double model_error = reference.residual_rms;  // ~ cubic's distance from a quadratic
  double balanced_gap = 0.0, plain_gap = 0.0;
  for (double t = 27000; t <= 38000; t += 500) {
    balanced_gap = std::max(balanced_gap, std::abs(balanced.Drift(t) - reference.Drift(t)));
    plain_gap = std::max(plain_gap, std::abs(plain.Drift(t) - reference.Drift(t)));
  }
  EXPECT_LT(balanced_gap, 0.1 * model_error);
  EXPECT_GT(plain_gap, 0.5 * model_error);
}

double UpCurve(double t) { return Quadratic(t) + 3000.0; }
double DownCurve(double t) { return Quadratic(t) - 3000.0; }

TEST(ThermalDriftFit, ReportsHysteresisBetweenRamps) {
  common::Rng rng(33);
  auto samples = Ramp(27000, 38000, 2000, ThermalSegment::kUpRamp, rng, 100.0, UpCurve);
  const auto down = Ramp(38000, 27000, 2000, ThermalSegment::kDownRamp, rng, 100.0, DownCurve);
  samples.insert(samples.end(), down.begin(), down.end());
  const ThermalDriftResult r = FitThermalDrift("gy", samples);
  ASSERT_TRUE(r.up && r.down);
  // Constructed gap 6000 counts; noise 100 counts over 2000 samples moves each curve by < 20.
  EXPECT_NEAR(r.hysteresis, 6000.0, 60.0);
  EXPECT_NEAR(r.up->Drift(30000), UpCurve(30000), 30.0);
}

TEST(ThermalDriftFit, RefusesTooFewTemperatures) {
  common::Rng rng(34);
  // Three soaks, 110-count bands: 3 bands < 4.
  std::vector<ThermalSample> samples;
  for (double t : {28060.0, 32010.0, 36080.0}) {  // 20-count soaks inside one band each
    const auto soak = Ramp(t, t + 20, 100, ThermalSegment::kSoak, rng, 10.0, Quadratic);
    samples.insert(samples.end(), soak.begin(), soak.end());
  }
  EXPECT_THAT(
      [&] { FitThermalDrift("ax2", samples); },
      ::testing::ThrowsMessage<DegenerateDesignError>(HasSubstr(
          "thermal fit of ax2 (all samples): design refused: the samples cover 3 "
          "temperature band(s) of 110 counts, at least 4 are needed (too few temperatures)")));
}

TEST(ThermalDriftFit, MissingRampDirectionIsReportedNotRefused) {
  common::Rng rng(35);
  const auto samples = Ramp(27000, 38000, 500, ThermalSegment::kUpRamp, rng, 10.0, Quadratic);
  const ThermalDriftResult r = FitThermalDrift("gz", samples);
  EXPECT_TRUE(r.up.has_value());
  EXPECT_FALSE(r.down.has_value());
  EXPECT_THAT(r.ramp_note,
              HasSubstr("thermal fit of gz (down-ramps): design refused: the samples "
                        "cover 0 temperature band(s)"));
  EXPECT_EQ(r.hysteresis, 0.0);
}

}  // namespace
}  // namespace adahrs::calib
