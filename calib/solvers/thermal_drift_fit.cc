#include "calib/solvers/thermal_drift_fit.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "calib/solvers/polynomial_fit.h"

namespace adahrs::calib {
namespace {

// Equal weight per temperature band: w_i = 1 / (samples in the band of sample i).
ThermalPolynomial FitSubset(const std::string& context,
                            const std::vector<ThermalSample>& samples,
                            const ThermalFitOptions& options) {
  std::map<long long, int> band_count;
  auto band_of = [&](double temp_cnt) {
    return static_cast<long long>(std::floor(temp_cnt / options.band_width_cnt));
  };
  for (const ThermalSample& s : samples) ++band_count[band_of(s.temp_cnt)];
  const int bands = static_cast<int>(band_count.size());
  if (bands < options.min_bands) {
    throw DegenerateDesignError(fmt::format(
        "{}: design refused: the samples cover {} temperature band(s) of {} counts, at least {} "
        "are needed (too few temperatures)",
        context,
        bands,
        options.band_width_cnt,
        options.min_bands));
  }
  PolynomialObservations obs;
  for (const ThermalSample& s : samples) {
    obs.x.push_back(s.temp_cnt);
    obs.z.push_back(s.value);
    obs.weights.push_back(1.0 / band_count[band_of(s.temp_cnt)]);
  }
  const PolynomialBasis basis = PolynomialBasis::Univariate(2, "t");
  const PolynomialFit fit = FitPolynomial(context,
                                          basis,
                                          obs,
                                          WeightKind::kBalancing,
                                          ErrorScale::kResidualVariance,
                                          options.least_squares);
  ThermalPolynomial out;
  for (int i = 0; i < 3; ++i) {
    out.k[i] = fit.raw_coefficients[i];
    out.k_se[i] = fit.raw_standard_errors[i];
  }
  out.covariance = fit.raw_covariance;
  out.temp_min_cnt = fit.x_min;
  out.temp_max_cnt = fit.x_max;
  out.bands = bands;
  out.samples = static_cast<int>(samples.size());
  out.residual_rms = fit.fit.residual_rms;
  out.condition_number = fit.fit.condition_number;
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
  result.all = FitSubset(fmt::format("thermal fit of {} (all samples)", channel), samples, options);

  auto direction =
      [&](ThermalSegment segment, const char* name, std::optional<ThermalPolynomial>* out) {
        std::vector<ThermalSample> subset;
        std::copy_if(samples.begin(),
                     samples.end(),
                     std::back_inserter(subset),
                     [&](const ThermalSample& s) { return s.segment == segment; });
        try {
          *out = FitSubset(fmt::format("thermal fit of {} ({})", channel, name), subset, options);
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
