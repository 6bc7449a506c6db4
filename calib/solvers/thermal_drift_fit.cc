#include "calib/solvers/thermal_drift_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "calib/solvers/polynomial_basis.h"

namespace adahrs::calib {
namespace {

using SegmentFilter = std::optional<ThermalSegment>;  // the samples fitted: one segment, or all

bool Selected(const ThermalSample& s, const SegmentFilter& filter) {
  return !filter || s.segment == *filter;
}

// Samples per temperature band (band index - first), over the selected samples.
struct BandCounts {
  long long first = 0;
  std::vector<int> count;
  int bands = 0;  ///< bands holding a sample
  int samples = 0;
  double temp_min_cnt = 0.0, temp_max_cnt = 0.0;
};

BandCounts CountBands(const std::vector<ThermalSample>& samples,
                      const SegmentFilter& filter,
                      double band_width_cnt,
                      const std::string& context) {
  BandCounts b;
  long long lo = 0, hi = -1;
  for (const ThermalSample& s : samples) {
    if (!Selected(s, filter)) continue;
    if (!std::isfinite(s.temp_cnt) || !std::isfinite(s.value)) {
      throw DegenerateDesignError(
          fmt::format("{}: design refused: observation {} is not finite or has a weight <= 0",
                      context,
                      b.samples));
    }
    const auto band = static_cast<long long>(std::floor(s.temp_cnt / band_width_cnt));
    if (b.samples == 0 || band < lo) lo = band;
    if (b.samples == 0 || band > hi) hi = band;
    b.temp_min_cnt = b.samples == 0 ? s.temp_cnt : std::min(b.temp_min_cnt, s.temp_cnt);
    b.temp_max_cnt = b.samples == 0 ? s.temp_cnt : std::max(b.temp_max_cnt, s.temp_cnt);
    ++b.samples;
  }
  b.first = lo;
  b.count.assign(static_cast<size_t>(hi - lo + 1), 0);
  for (const ThermalSample& s : samples) {
    if (!Selected(s, filter)) continue;
    ++b.count[static_cast<size_t>(static_cast<long long>(std::floor(s.temp_cnt / band_width_cnt)) -
                                  lo)];
  }
  for (int c : b.count) b.bands += c > 0 ? 1 : 0;
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

NormalEquations Accumulate(const std::vector<ThermalSample>& samples,
                           const SegmentFilter& filter,
                           const BandCounts& bands,
                           const InputScaling& scaling,
                           double band_width_cnt) {
  // Per band: sum u^k (k = 0..4) and sum u^k y (k = 0..2).
  std::vector<std::array<double, 8>> per_band(bands.count.size(), std::array<double, 8>{});
  for (const ThermalSample& s : samples) {
    if (!Selected(s, filter)) continue;
    const double u = scaling.Normalise(s.temp_cnt);
    const double u2 = u * u;
    auto& a = per_band[static_cast<size_t>(
        static_cast<long long>(std::floor(s.temp_cnt / band_width_cnt)) - bands.first)];
    a[0] += 1.0;
    a[1] += u;
    a[2] += u2;
    a[3] += u2 * u;
    a[4] += u2 * u2;
    a[5] += s.value;
    a[6] += u * s.value;
    a[7] += u2 * s.value;
  }
  std::array<double, 5> moment{}, moment_sq{};
  NormalEquations ne;
  for (size_t b = 0; b < per_band.size(); ++b) {
    if (bands.count[b] == 0) continue;
    const double w = 1.0 / bands.count[b];
    for (int k = 0; k < 5; ++k) {
      moment[k] += w * per_band[b][k];
      moment_sq[k] += w * w * per_band[b][k];
    }
    for (int k = 0; k < 3; ++k) ne.rhs[k] += w * per_band[b][5 + k];
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

// Equal weight per temperature band: w_i = 1 / (samples in the band of sample i). The rows are
// never held as a design matrix: the fit streams them into per-band sums (normal equations in the
// normalised temperature, where the equilibrated design's condition number is small), then a
// second pass takes the residuals.
ThermalPolynomial FitSubset(const std::string& context,
                            const std::vector<ThermalSample>& samples,
                            const SegmentFilter& filter,
                            const ThermalFitOptions& options) {
  const BandCounts bands = CountBands(samples, filter, options.band_width_cnt, context);
  if (bands.bands < options.min_bands) {
    throw DegenerateDesignError(fmt::format(
        "{}: design refused: the samples cover {} temperature band(s) of {} counts, at least {} "
        "are needed (too few temperatures)",
        context,
        bands.bands,
        options.band_width_cnt,
        options.min_bands));
  }
  const InputScaling scaling = InputScaling::FromRange(bands.temp_min_cnt, bands.temp_max_cnt);
  const NormalEquations ne = Accumulate(samples, filter, bands, scaling, options.band_width_cnt);
  Eigen::Matrix3d m_inv;
  double condition = 0.0;
  const Eigen::Vector3d beta = SolveNormal(ne, options.least_squares, context, &m_inv, &condition);
  double sum_sq = 0.0;
  for (const ThermalSample& s : samples) {
    if (!Selected(s, filter)) continue;
    const double u = scaling.Normalise(s.temp_cnt);
    const double r = s.value - (beta[0] + beta[1] * u + beta[2] * (u * u));
    sum_sq += r * r;
  }
  const double sigma2 = sum_sq / (bands.samples - 3);
  const Eigen::Matrix3d covariance = sigma2 * m_inv * ne.g * m_inv;  // the sandwich (kBalancing)
  const PolynomialBasis basis = PolynomialBasis::Univariate(2, "t");
  const Eigen::Matrix3d t = basis.NormalisedToRaw(scaling, InputScaling{});
  const Eigen::Vector3d raw = t * beta;
  ThermalPolynomial out;
  out.covariance = t * covariance * t.transpose();
  for (int i = 0; i < 3; ++i) {
    out.k[i] = raw[i];
    out.k_se[i] = std::sqrt(out.covariance(i, i));
  }
  out.temp_min_cnt = bands.temp_min_cnt;
  out.temp_max_cnt = bands.temp_max_cnt;
  out.bands = bands.bands;
  out.samples = bands.samples;
  out.residual_rms = std::sqrt(sum_sq / bands.samples);
  out.condition_number = condition;
  return out;
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
  result.all = FitSubset(
      fmt::format("thermal fit of {} (all samples)", channel), samples, std::nullopt, options);

  auto direction =
      [&](ThermalSegment segment, const char* name, std::optional<ThermalPolynomial>* out) {
        try {
          *out = FitSubset(
              fmt::format("thermal fit of {} ({})", channel, name), samples, segment, options);
        } catch (const DegenerateDesignError& e) {
          result.ramp_note += (result.ramp_note.empty() ? "" : "; ") + std::string(e.what());
        }
      };
  direction(ThermalSegment::kUpRamp, "up-ramps", &result.up);
  direction(ThermalSegment::kDownRamp, "down-ramps", &result.down);

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
