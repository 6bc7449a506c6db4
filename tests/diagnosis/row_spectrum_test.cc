// Row spectra against series of known content: a sinusoid's frequency and amplitude, no line in
// coloured noise (white through a one-pole filter, plus a random walk), gaps honoured.
#include "diagnosis/row_spectrum.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace adahrs::diagnosis {
namespace {

struct Series {
  std::vector<double> t_s, y;
};

// AR(1) noise (pole at `pole`) of unit innovation, a random walk of `walk` per row, a sinusoid.
Series Make(uint64_t seed,
            size_t rows,
            double dt_s,
            double pole,
            double walk,
            double amplitude,
            double f_hz) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01;
  Series s;
  double ar = 0.0, rw = 0.0;
  for (size_t i = 0; i < rows; ++i) {
    ar = pole * ar + n01(rng);
    rw += walk * n01(rng);
    const double t = i * dt_s;
    s.t_s.push_back(t);
    s.y.push_back(ar + rw + amplitude * std::sin(2.0 * M_PI * f_hz * t + 0.4));
  }
  return s;
}

RowSpectra Spectra(const Series& s, double dt_s) {
  RowSpectra spectra(1, dt_s);
  spectra.AddSegment(
      0, s.y.size(), [&](size_t i) { return s.t_s[i]; }, [&](size_t i, int) { return s.y[i]; });
  return spectra;
}

TEST(RowSpectrum, WhiteNoiseGivesItsVarianceOverTheWindowPerBin) {
  const Series s = Make(1, 512 * 400, 0.01, 0.0, 0.0, 0.0, 1.0);
  const RowSpectra spectra = Spectra(s, 0.01);
  ASSERT_EQ(spectra.windows(), 400);
  const std::vector<double> p = spectra.MeanPower(0);
  double mean = 0.0;
  for (size_t k = 10; k < 250; ++k) mean += p[k] / 240.0;
  EXPECT_NEAR(mean * 512, 1.0, 0.03);
}

TEST(RowSpectrum, FindsASinusoidAtAFifthOfTheNoiseWithItsAmplitude) {
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    const double f_hz = 2.0 + 3.7 * seed;
    const Series s = Make(seed, 512 * 300, 0.01, 0.9, 0.01, 0.2 * 2.3, f_hz);  // AR(1) sd 2.3
    const std::vector<PeriodicLine> lines = FindPeriodicLines(Spectra(s, 0.01), 0, 1e-3);
    for (const PeriodicLine& l : lines)
      std::printf("seed %d: %.3f Hz amplitude %.3f z %.1f\n",
                  static_cast<int>(seed),
                  l.frequency_hz,
                  l.amplitude,
                  l.z);
    ASSERT_EQ(lines.size(), 1u) << "seed " << seed;
    EXPECT_NEAR(lines[0].frequency_hz, f_hz, 0.1);
    EXPECT_NEAR(lines[0].amplitude, 0.46, 0.07);
    EXPECT_EQ(lines[0].segments.size(), 1u);
  }
}

TEST(RowSpectrum, ColouredNoiseGivesNoLineOnFiftySeeds) {
  int with_lines = 0;
  for (uint64_t seed = 100; seed < 150; ++seed) {
    const Series s = Make(seed, 512 * 200, 0.01, 0.95, 0.05, 0.0, 1.0);
    if (!FindPeriodicLines(Spectra(s, 0.01), 0, 1e-3).empty()) ++with_lines;
  }
  EXPECT_LE(with_lines, 1);  // level 1e-3 per series: 0.05 expected
}

TEST(RowSpectrum, AGapClosesAWindowAndTheNextStartsAfterIt) {
  Series s = Make(3, 2000, 0.01, 0.0, 0.0, 0.0, 1.0);
  for (size_t i = 700; i < s.t_s.size(); ++i)
    s.t_s[i] += 0.5;  // a gap of 50 rows' time after row 699
  const RowSpectra spectra = Spectra(s, 0.01);
  // Rows 0-511 fill one window; 512-699 are too few; 700-1211 and 1212-1723 fill two more.
  EXPECT_EQ(spectra.windows(), 3);
}

TEST(RowSpectrum, MedianIntervalIgnoresRepeatsAndGaps) {
  EXPECT_DOUBLE_EQ(MedianInterval({0.0, 0.01, 0.02, 0.02, 0.03, 5.0, 5.01}), 0.01);
  EXPECT_EQ(MedianInterval({}), 0.0);
}

}  // namespace
}  // namespace adahrs::diagnosis
