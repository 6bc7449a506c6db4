#include "calib/solvers/thermal_drift_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "calib/solvers/polynomial_basis.h"

namespace adahrs::calib {
namespace {

// The three sets of samples fitted (every sample, the up-ramps', the down-ramps'), each fitted as
// if alone; one pass over the samples serves all three.
constexpr int kSubsets = 3;
constexpr std::array<const char*, kSubsets> kSubsetNames = {
    "all samples", "up-ramps", "down-ramps"};

// The subsets a sample belongs to: every sample to the first, a ramp's to its direction's too.
int SecondSubset(const ThermalSample& s) {
  return s.segment == ThermalSegment::kUpRamp ? 1 : s.segment == ThermalSegment::kDownRamp ? 2 : -1;
}

template <typename Visit>
void ForEachSubset(const ThermalSample& s, Visit visit) {
  visit(0);
  if (const int second = SecondSubset(s); second >= 0) visit(second);
}

long long BandOf(const ThermalSample& s, double band_width_cnt) {
  return static_cast<long long>(std::floor(s.temp_cnt / band_width_cnt));
}

// Samples per temperature band (band index - first), over one subset's samples.
struct BandCounts {
  long long first = 0;
  std::vector<int> count;
  int bands = 0;  ///< bands holding a sample
  int samples = 0;
  double temp_min_cnt = 0.0, temp_max_cnt = 0.0;
};

std::array<BandCounts, kSubsets> CountBands(const std::vector<ThermalSample>& samples,
                                            double band_width_cnt,
                                            const std::string& context) {
  std::array<BandCounts, kSubsets> b;
  std::array<long long, kSubsets> lo{}, hi{};
  for (const ThermalSample& s : samples) {
    if (!std::isfinite(s.temp_cnt) || !std::isfinite(s.value)) {
      throw DegenerateDesignError(
          fmt::format("{} ({}): design refused: observation {} is not finite or has a weight <= 0",
                      context,
                      kSubsetNames[0],
                      b[0].samples));
    }
    const long long band = BandOf(s, band_width_cnt);
    ForEachSubset(s, [&](int k) {
      BandCounts& c = b[k];
      if (c.samples == 0 || band < lo[k]) lo[k] = band;
      if (c.samples == 0 || band > hi[k]) hi[k] = band;
      c.temp_min_cnt = c.samples == 0 ? s.temp_cnt : std::min(c.temp_min_cnt, s.temp_cnt);
      c.temp_max_cnt = c.samples == 0 ? s.temp_cnt : std::max(c.temp_max_cnt, s.temp_cnt);
      ++c.samples;
    });
  }
  for (int k = 0; k < kSubsets; ++k) {
    b[k].first = lo[k];
    b[k].count.assign(b[k].samples == 0 ? 0 : static_cast<size_t>(hi[k] - lo[k] + 1), 0);
  }
  for (const ThermalSample& s : samples) {
    const long long band = BandOf(s, band_width_cnt);
    ForEachSubset(s, [&](int k) { ++b[k].count[static_cast<size_t>(band - b[k].first)]; });
  }
  for (BandCounts& c : b) {
    for (int n : c.count) c.bands += n > 0 ? 1 : 0;
  }
  return b;
}

// The band-weighted normal equations of the quadratic in normalised temperature u (on [-1, 1]),
// accumulated per band (w is constant within a band) and then over the bands:
//   M = sum w a a', A'Wy = sum w a y, G = sum w^2 a a' (the sandwich's middle), a = (1, u, u^2).
struct NormalEquations {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
};

// Per band: sum u^k (k = 0..4) and sum u^k y (k = 0..2), each a compensated (Neumaier) sum: a
// band holds up to tens of thousands of rows of a gyro's ~4e6 counts, whose plain sum loses the
// last ~1e-13 of the level (1e-7 counts of the fitted null); compensated, the sums are good to
// the last bit, so any exact formation of the same normal equations gives the same constants.
struct BandSums {
  std::array<double, 8> sum{};
  std::array<double, 8> compensation{};
  void Add(int k, double x) {
    const double t = sum[k] + x;
    compensation[k] += std::abs(sum[k]) >= std::abs(x) ? (sum[k] - t) + x : (x - t) + sum[k];
    sum[k] = t;
  }
  double Total(int k) const { return sum[k] + compensation[k]; }
};

// One subset's fit as it goes: its bands, scaling, sums and solution; `error` says why it has
// none (too few bands, a degenerate design).
struct SubsetFit {
  BandCounts bands;
  InputScaling scaling;
  std::vector<BandSums> per_band;
  NormalEquations ne;
  Eigen::Vector3d beta = Eigen::Vector3d::Zero();
  Eigen::Matrix3d m_inv = Eigen::Matrix3d::Zero();
  double condition = 0.0;
  double sum_sq = 0.0;
  std::string error;
  bool ok() const { return error.empty(); }
};

// Per band: sum u^k (k = 0..4) and sum u^k y (k = 0..2) of every usable subset, in one pass.
void AccumulateBands(const std::vector<ThermalSample>& samples,
                     double band_width_cnt,
                     std::array<SubsetFit, kSubsets>& fits) {
  for (SubsetFit& f : fits) {
    if (f.ok()) f.per_band.assign(f.bands.count.size(), BandSums{});
  }
  for (const ThermalSample& s : samples) {
    const long long band = BandOf(s, band_width_cnt);
    ForEachSubset(s, [&](int k) {
      SubsetFit& f = fits[k];
      if (!f.ok()) return;
      const double u = f.scaling.Normalise(s.temp_cnt);
      const double u2 = u * u;
      auto& a = f.per_band[static_cast<size_t>(band - f.bands.first)];
      a.Add(0, 1.0);
      a.Add(1, u);
      a.Add(2, u2);
      a.Add(3, u2 * u);
      a.Add(4, u2 * u2);
      a.Add(5, s.value);
      a.Add(6, u * s.value);
      a.Add(7, u2 * s.value);
    });
  }
}

// The band-weighted normal equations from the per-band sums.
NormalEquations NormalFromBands(const SubsetFit& f) {
  std::array<double, 5> moment{}, moment_sq{};
  NormalEquations ne;
  for (size_t b = 0; b < f.per_band.size(); ++b) {
    if (f.bands.count[b] == 0) continue;
    const double w = 1.0 / f.bands.count[b];
    for (int k = 0; k < 5; ++k) {
      moment[k] += w * f.per_band[b].Total(k);
      moment_sq[k] += w * w * f.per_band[b].Total(k);
    }
    for (int k = 0; k < 3; ++k) ne.rhs[k] += w * f.per_band[b].Total(5 + k);
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      ne.m(i, j) = moment[i + j];
      ne.g(i, j) = moment_sq[i + j];
    }
  }
  return ne;
}

// Solves the equilibrated normal equations with the driver's rank and condition tests
// (linear_least_squares.h); the singular values of the equilibrated weighted design are the square
// roots of the equilibrated M's eigenvalues. Returns the normalised coefficients and fills the
// scaled inverse, the scaling and the condition number.
Eigen::Vector3d SolveNormal(const NormalEquations& ne,
                            const LeastSquaresOptions& options,
                            const std::string& context,
                            Eigen::Matrix3d* m_inv,
                            double* condition) {
  const Eigen::Vector3d d = ne.m.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::Matrix3d ms = d.asDiagonal() * ne.m * d.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(ms);
  const Eigen::Vector3d s = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();  // ascending
  int rank = 0;
  for (int j = 0; j < 3; ++j) rank += s[j] > options.rank_tolerance * s[2] ? 1 : 0;
  *condition = s[0] > 0.0 ? s[2] / s[0] : std::numeric_limits<double>::infinity();
  if (rank < 3 || !(*condition <= options.max_condition)) {
    const Eigen::Vector3d v = eig.eigenvectors().col(0);
    const double largest = v.cwiseAbs().maxCoeff();
    const std::array<const char*, 3> names = {"1", "t", "t^2"};
    std::string null;
    for (int j = 0; j < 3; ++j) {
      if (std::abs(v[j]) < 0.1 * largest) continue;
      null += fmt::format("{}{:+.3f} {}", null.empty() ? "" : " ", v[j], names[j]);
    }
    throw DegenerateDesignError(
        fmt::format("{}: design refused: rank {} of 3 terms, condition number {:.3g} (limit "
                    "{:.3g}); near-null combination of the normalised terms: {}",
                    context,
                    rank,
                    *condition,
                    options.max_condition,
                    null));
  }
  const Eigen::Matrix3d ms_inv = ms.llt().solve(Eigen::Matrix3d::Identity());
  *m_inv = d.asDiagonal() * ms_inv * d.asDiagonal();
  return d.asDiagonal() * (ms_inv * d.cwiseProduct(ne.rhs));
}

// The fitted polynomial in raw temperature counts with its sandwich covariance.
ThermalPolynomial Polynomial(const SubsetFit& f) {
  const double sigma2 = f.sum_sq / (f.bands.samples - 3);
  const Eigen::Matrix3d covariance = sigma2 * f.m_inv * f.ne.g * f.m_inv;  // kBalancing
  const PolynomialBasis basis = PolynomialBasis::Univariate(2, "t");
  const Eigen::Matrix3d t = basis.NormalisedToRaw(f.scaling, InputScaling{});
  const Eigen::Vector3d raw = t * f.beta;
  ThermalPolynomial out;
  out.covariance = t * covariance * t.transpose();
  for (int i = 0; i < 3; ++i) {
    out.k[i] = raw[i];
    out.k_se[i] = std::sqrt(out.covariance(i, i));
  }
  out.temp_min_cnt = f.bands.temp_min_cnt;
  out.temp_max_cnt = f.bands.temp_max_cnt;
  out.bands = f.bands.bands;
  out.samples = f.bands.samples;
  out.residual_rms = std::sqrt(f.sum_sq / f.bands.samples);
  out.condition_number = f.condition;
  return out;
}

// Equal weight per temperature band: w_i = 1 / (samples in the band of sample i). The rows are
// never held as a design matrix: the fits stream them into per-band sums (normal equations in
// the normalised temperature, where the equilibrated design's condition number is small), then a
// last pass takes the residuals. The fit of all samples throws its DegenerateDesignError; a ramp
// direction's is kept in its `error`.
std::array<SubsetFit, kSubsets> FitSubsets(const std::string& channel,
                                           const std::vector<ThermalSample>& samples,
                                           const ThermalFitOptions& options) {
  const std::string context = fmt::format("thermal fit of {}", channel);
  std::array<SubsetFit, kSubsets> fits;
  const std::array<BandCounts, kSubsets> bands =
      CountBands(samples, options.band_width_cnt, context);
  for (int k = 0; k < kSubsets; ++k) {
    SubsetFit& f = fits[k];
    f.bands = bands[k];
    if (f.bands.bands < options.min_bands) {
      f.error = fmt::format(
          "{} ({}): design refused: the samples cover {} temperature band(s) of {} counts, at "
          "least {} are needed (too few temperatures)",
          context,
          kSubsetNames[k],
          f.bands.bands,
          options.band_width_cnt,
          options.min_bands);
      if (k == 0) throw DegenerateDesignError(f.error);
      continue;
    }
    f.scaling = InputScaling::FromRange(f.bands.temp_min_cnt, f.bands.temp_max_cnt);
  }
  AccumulateBands(samples, options.band_width_cnt, fits);
  for (int k = 0; k < kSubsets; ++k) {
    SubsetFit& f = fits[k];
    if (!f.ok()) continue;
    f.ne = NormalFromBands(f);
    try {
      f.beta = SolveNormal(f.ne,
                           options.least_squares,
                           context + " (" + kSubsetNames[k] + ")",
                           &f.m_inv,
                           &f.condition);
    } catch (const DegenerateDesignError& e) {
      if (k == 0) throw;
      f.error = e.what();
    }
  }
  for (const ThermalSample& s : samples) {
    ForEachSubset(s, [&](int k) {
      SubsetFit& f = fits[k];
      if (!f.ok()) return;
      const double u = f.scaling.Normalise(s.temp_cnt);
      const double r = s.value - (f.beta[0] + f.beta[1] * u + f.beta[2] * (u * u));
      f.sum_sq += r * r;
    });
  }
  return fits;
}

}  // namespace

double ThermalPolynomial::DriftStandardError(double temp_cnt) const {
  const Eigen::Vector3d row(1.0, temp_cnt, temp_cnt * temp_cnt);
  return std::sqrt(row.dot(covariance * row));
}

ThermalDriftResult FitThermalDrift(const std::string& channel,
                                   const std::vector<ThermalSample>& samples,
                                   const ThermalFitOptions& options) {
  ThermalDriftResult result;
  const std::array<SubsetFit, kSubsets> fits = FitSubsets(channel, samples, options);
  result.all = Polynomial(fits[0]);
  for (int k = 1; k < kSubsets; ++k) {
    std::optional<ThermalPolynomial>& out = k == 1 ? result.up : result.down;
    if (fits[k].ok()) {
      out = Polynomial(fits[k]);
    } else {
      result.ramp_note += (result.ramp_note.empty() ? "" : "; ") + fits[k].error;
    }
  }

  if (result.up && result.down) {
    const double lo = std::max(result.up->temp_min_cnt, result.down->temp_min_cnt);
    const double hi = std::min(result.up->temp_max_cnt, result.down->temp_max_cnt);
    constexpr int kGridPoints = 101;
    for (int i = 0; lo < hi && i < kGridPoints; ++i) {
      const double t = lo + (hi - lo) * i / (kGridPoints - 1);
      const double gap = std::abs(result.up->Drift(t) - result.down->Drift(t));
      if (gap > result.hysteresis) {
        result.hysteresis = gap;
        result.hysteresis_at_temp_cnt = t;
      }
    }
  }
  return result;
}

}  // namespace adahrs::calib
