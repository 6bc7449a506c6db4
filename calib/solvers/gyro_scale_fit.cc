#include "calib/solvers/gyro_scale_fit.h"

#include <cmath>
#include <set>

#include <fmt/format.h>

#include "calib/solvers/polynomial_fit.h"

namespace adahrs::calib {

GyroScaleEstimate FitGyroScale(const std::string& gyro,
                               const std::vector<GyroRateMean>& steps,
                               const GyroScaleOptions& options) {
  const std::string context = fmt::format("gyro scale fit of {}", gyro);
  // The null step: its mean reported rate is 0 to within the table's settling (a table still
  // settling by 1e-4 deg/s for a tenth of the acquisition reports a mean of -1e-5).
  const GyroRateMean* zero = nullptr;
  std::set<double> rates;
  for (const GyroRateMean& s : steps) {
    rates.insert(s.rate_dps);
    if (std::abs(s.rate_dps) <= kNullStepTolerance_dps &&
        (zero == nullptr || std::abs(s.rate_dps) < std::abs(zero->rate_dps))) {
      zero = &s;
    }
  }
  if (zero == nullptr) {
    throw DegenerateDesignError(
        fmt::format("{}: design refused: no 0 deg/s step to normalise the means by", context));
  }
  if (static_cast<int>(rates.size()) < options.min_rates) {
    throw DegenerateDesignError(
        fmt::format("{}: design refused: {} distinct rates, at least {} are needed (too few rates)",
                    context,
                    rates.size(),
                    options.min_rates));
  }
  PolynomialObservations obs;
  for (const GyroRateMean& s : steps) {
    obs.x.push_back(s.t_cnt - zero->t_cnt);
    obs.z.push_back(s.rate_dps);
  }
  const PolynomialBasis basis = PolynomialBasis::Univariate(3, "d");
  const PolynomialFit fit = FitPolynomial(context,
                                          basis,
                                          obs,
                                          WeightKind::kInverseVariance,
                                          ErrorScale::kResidualVariance,
                                          options.least_squares);
  GyroScaleEstimate out;
  out.fit.null_cnt = zero->t_cnt;
  out.null_se_cnt = zero->t_cnt_se;
  for (int i = 0; i < 4; ++i) {
    out.fit.l[i] = fit.raw_coefficients[i];
    out.l_se[i] = fit.raw_standard_errors[i];
  }
  out.covariance = fit.raw_covariance;
  out.residual_rms_dps = fit.fit.residual_rms;
  out.rates = static_cast<int>(rates.size());
  out.condition_number = fit.fit.condition_number;
  return out;
}

}  // namespace adahrs::calib
