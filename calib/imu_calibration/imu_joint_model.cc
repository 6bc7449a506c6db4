#include "calib/imu_calibration/imu_joint_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "calib/imu_calibration/gyro_bias_covariance.h"
#include "calib/imu_calibration/imu_reference_fit.h"
#include "common/median.h"
#include "common/units.h"

namespace adahrs::calib::joint_fit {

double OwnStimulus(const ChannelModel& m, const ImuObservation& o) {
  return m.gyro() ? o.w_B_dps[m.channel - 6] : o.f_B_g[kAxisOfChannel[m.channel]];
}

double ScaledStimulus(const ChannelModel& m, const ImuObservation& o) {
  const double s = OwnStimulus(m, o);
  return m.gyro() ? s + m.nl2_per_dps * s * s + m.nl3_per_dps2 * s * s * s : s;
}

double TauPowerMean(const ImuObservation& o, int sensor, int p) {
  const double moment[kMaxThermalOrder + 1] = {
      1.0, o.t_mean_cnt[sensor], o.t2_mean_cnt2[sensor], o.t3_mean_cnt3[sensor]};
  double sum = 0.0, binomial = 1.0;
  for (int i = p; i >= 0; --i) {
    sum += binomial * moment[i] * std::pow(-kTempCentre_cnt, p - i);
    binomial = binomial * i / (p - i + 1);
  }
  return sum / std::pow(kTempSpan_cnt, p);
}

Eigen::RowVectorXd DesignRow(const ChannelModel& m, const ImuObservation& o) {
  Eigen::RowVectorXd row(m.size());
  int k = 0;
  row[k++] = 1.0;
  for (int p = 1; p <= m.order; ++p) row[k++] = TauPowerMean(o, m.sensor(), p);
  if (!m.gyro()) {
    for (int a = 0; a < 3; ++a) row[k++] = o.f_B_g[a];
  } else {
    for (int a = 0; a < 3; ++a) row[k++] = o.w_B_dps[a];
    const double w = o.w_B_dps[m.channel - 6];
    row[k++] = w * w;
    row[k++] = w * w * w;
  }
  const double own = OwnStimulus(m, o);
  const double scaled = ScaledStimulus(m, o);
  for (int p = 1; p <= m.scale_order; ++p) row[k++] = TauPowerMean(o, m.sensor(), p) * scaled;
  if (m.quadratic) row[k++] = own * own;
  if (m.g_sensitivity) {
    for (int a = 0; a < 3; ++a) row[k++] = o.f_B_g[a];
  }
  if (m.lag) {
    // A die lagging its thermometer by L reads xi(tau - L tau_dot) ~ xi(tau) - L tau_dot xi'(tau):
    // tau_dot and tau_dot tau (per s; xi' taken as linear in tau).
    const double tau_dot = o.t_rate_cnt_per_s[m.sensor()] / kTempSpan_cnt;
    row[k++] = tau_dot;
    row[k++] = tau_dot * TauPowerMean(o, m.sensor(), 1);
  }
  return row;
}

std::vector<std::string> TermNames(const ChannelModel& m) {
  std::vector<std::string> names = {"offset"};
  for (int p = 1; p <= m.order; ++p) names.push_back(p == 1 ? "tau" : "tau^" + std::to_string(p));
  if (!m.gyro()) {
    names.insert(names.end(), {"f_x", "f_y", "f_z"});
  } else {
    names.insert(names.end(), {"w_x", "w_y", "w_z", "w^2", "w^3"});
  }
  const std::string own = m.gyro() ? "w_axis" : "f_axis";
  for (int p = 1; p <= m.scale_order; ++p) {
    names.push_back((p == 1 ? std::string("tau ") : "tau^" + std::to_string(p) + " ") + own);
  }
  if (m.quadratic) names.push_back("f_axis^2");
  if (m.g_sensitivity) names.insert(names.end(), {"g f_x", "g f_y", "g f_z"});
  if (m.lag) names.insert(names.end(), {"tau_dot", "tau_dot tau"});
  return names;
}

double MedianThermalCount(const std::vector<ImuObservation>& obs) {
  std::vector<double> counts;
  for (const ImuObservation& o : obs) {
    if (o.thermal) counts.push_back(o.count);
  }
  return counts.empty() ? 1.0 : common::Median(counts);
}

double Variance(const ImuObservation& o,
                int ch,
                double n_thermal,
                bool datasheet,
                const ImuDatasheetNoise& noise) {
  const double n = o.thermal ? n_thermal : o.count;
  if (!datasheet) {
    // A measured spread below half the datasheet noise is not credible (few samples, or samples
    // identical after quantisation): the variance is not allowed below a quarter of the
    // datasheet's.
    const double measured = o.u_sd[ch] * o.u_sd[ch] / n;
    return std::max(measured, 0.25 * Variance(o, ch, n_thermal, true, noise));
  }
  if (ch < 6) {
    // Filtered white noise sampled every frame: stationary variance N^2 / (4 tau) with lag-one
    // correlation rho = exp(-T / tau); a mean of n such samples has variance
    // sigma^2 / n * (1 + rho) / (1 - rho).
    const double sigma_g =
        noise.accel_density_ug_per_rthz * 1e-6 / std::sqrt(4.0 * noise.accel_filter_tau_s);
    const double rho = std::exp(-noise.frame_period_s / noise.accel_filter_tau_s);
    const double sigma_duty = sigma_g * noise.accel_sensitivity_duty_per_g;
    return sigma_duty * sigma_duty / n * (1.0 + rho) / (1.0 - rho);
  }
  // Per-frame rate (output filter + 16 conversions) has one-sided low-frequency PSD N^2, so a
  // mean over T = n frames has variance N^2 / (2 T).
  const double var_dps2 = noise.gyro_density_dps_per_rthz * noise.gyro_density_dps_per_rthz /
                          (2.0 * n * noise.frame_period_s);
  return var_dps2 * noise.gyro_cnt_per_dps * noise.gyro_cnt_per_dps;
}

LinearFit Solve(const std::string& serial,
                ChannelModel& m,
                const std::vector<ImuObservation>& obs,
                const std::vector<size_t>& use,
                double n_thermal,
                bool datasheet,
                const ImuJointOptions& options,
                const Eigen::MatrixXd& bias_cnt2,
                BiasWander wander,
                double model_variance) {
  const ImuDatasheetNoise& noise = options.noise;
  const long n = static_cast<long>(use.size());
  LinearLeastSquaresProblem p;
  p.context = "unit " + serial + " joint model of " + common::kImuChannelNames[m.channel];
  p.term_names = TermNames(m);
  Eigen::MatrixXd design(n, m.size());
  Eigen::VectorXd y(n), variance(n);
  for (long r = 0; r < n; ++r) {
    const ImuObservation& o = obs[use[static_cast<size_t>(r)]];
    design.row(r) = DesignRow(m, o);
    y[r] = o.u_mean[m.channel];
    variance[r] = Variance(o, m.channel, n_thermal, datasheet, noise) + model_variance;
    if (wander != BiasWander::kNone)
      variance[r] += bias_cnt2(use[static_cast<size_t>(r)], use[static_cast<size_t>(r)]);
  }
  if (wander == BiasWander::kCorrelated) {
    // Whitening: with Sigma = L L', the rows L^-1 A and L^-1 y have unit independent errors.
    Eigen::MatrixXd sigma(n, n);
    for (long r = 0; r < n; ++r) {
      for (long c = 0; c < n; ++c)
        sigma(r, c) = bias_cnt2(use[static_cast<size_t>(r)], use[static_cast<size_t>(c)]);
      sigma(r, r) = variance[r];
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(sigma);
    if (llt.info() != Eigen::Success) {
      throw DegenerateDesignError(p.context +
                                  ": the observations' covariance (own variance plus gyro "
                                  "bias wander) is not positive definite");
    }
    p.design = llt.matrixL().solve(design);
    p.observations = llt.matrixL().solve(y);
  } else {
    p.design = design;
    p.observations = y;
    p.weights = options.unit_weights && !datasheet ? Eigen::VectorXd::Ones(n)
                                                   : Eigen::VectorXd(variance.cwiseInverse());
  }
  p.weight_kind = WeightKind::kInverseVariance;
  p.error_scale = datasheet ? ErrorScale::kKnownVariance : ErrorScale::kResidualVariance;
  LinearFit fit = SolveLinearLeastSquares(p);
  // Residuals in the channel's units (the driver's are of the whitened rows).
  const Eigen::VectorXd residual = y - design * fit.coefficients;
  fit.residual_rms = n > 0 ? std::sqrt(residual.squaredNorm() / static_cast<double>(n)) : 0.0;
  fit.max_abs_residual = n > 0 ? residual.cwiseAbs().maxCoeff() : 0.0;
  return fit;
}

double HeldOutSquares(const std::string& serial,
                      ChannelModel& m,
                      const std::vector<ImuObservation>& obs,
                      const std::vector<size_t>& train,
                      const std::vector<size_t>& test,
                      double n_thermal,
                      const ImuJointOptions& options,
                      const Eigen::MatrixXd& bias_cnt2,
                      BiasWander wander) {
  const LinearFit fit = Solve(serial, m, obs, train, n_thermal, false, options, bias_cnt2, wander);
  double sum = 0.0;
  for (size_t i : test) {
    const double r = obs[i].u_mean[m.channel] - DesignRow(m, obs[i]).dot(fit.coefficients);
    const double wander_cnt2 = wander == BiasWander::kNone ? 0.0 : bias_cnt2(i, i);
    sum += r * r / (Variance(obs[i], m.channel, n_thermal, false, options.noise) + wander_cnt2);
  }
  return sum;
}

int ChooseOrder(const std::string& serial,
                int ch,
                const std::vector<ImuObservation>& obs,
                double n_thermal,
                const ImuJointOptions& options,
                const Eigen::MatrixXd& bias_cnt2,
                BiasWander wander,
                JointChannelDiagnostics* report) {
  std::vector<size_t> thermal, other;
  for (size_t i = 0; i < obs.size(); ++i) (obs[i].thermal ? thermal : other).push_back(i);
  if (static_cast<int>(thermal.size()) < 4 * options.folds) return 2;
  double best = std::numeric_limits<double>::infinity();
  int best_order = 2;
  std::vector<double> scores;
  for (int order = 0; order <= kMaxThermalOrder; ++order) {
    double sum = 0.0;
    for (int fold = 0; fold < options.folds; ++fold) {
      std::vector<size_t> train = other, test;
      for (size_t k = 0; k < thermal.size(); ++k) {
        (static_cast<int>(k) % options.folds == fold ? test : train).push_back(thermal[k]);
      }
      ChannelModel m;
      m.channel = ch;
      m.order = order;
      sum += HeldOutSquares(serial, m, obs, train, test, n_thermal, options, bias_cnt2, wander);
    }
    const double score = std::sqrt(sum / static_cast<double>(thermal.size()));
    scores.push_back(score);
    if (score < best) {
      best = score;
      best_order = order;
    }
  }
  report->held_out_normalised_rms_by_order = scores;
  return best_order;
}

// The acquisitions' temperature levels for a channel's scale factor: observations (not thermal
// bands) whose stimulus on the channel's own axis is at least 0.5 g or 0.5 deg/s, grouped by
// their mean TEMP count within kScaleLevelGap_cnt (2 degC) of a level's first member.
constexpr double kScaleLevelGap_cnt = 220.0;

std::vector<int> ScaleLevels(const ChannelModel& m,
                             const std::vector<ImuObservation>& obs,
                             int* level_count) {
  std::vector<double> levels;
  std::vector<int> level_of(obs.size(), -1);
  for (size_t i = 0; i < obs.size(); ++i) {
    if (obs[i].thermal || std::abs(OwnStimulus(m, obs[i])) < 0.5) continue;
    const double t = obs[i].t_mean_cnt[m.sensor()];
    size_t l = 0;
    while (l < levels.size() && std::abs(levels[l] - t) > kScaleLevelGap_cnt) ++l;
    if (l == levels.size()) levels.push_back(t);
    level_of[i] = static_cast<int>(l);
  }
  *level_count = static_cast<int>(levels.size());
  return level_of;
}

// Scale-factor order 0..3 by leave-one-temperature-level-out error: each level's acquisitions
// predicted by a fit without them (the thermal bands always in), normalised by their noise.
constexpr int kGyroMinScaleOrder = 2;

int ChooseScaleOrder(const std::string& serial,
                     const ChannelModel& base,
                     const std::vector<ImuObservation>& obs,
                     double n_thermal,
                     const ImuJointOptions& options,
                     const Eigen::MatrixXd& bias_cnt2,
                     BiasWander wander,
                     JointChannelDiagnostics* report) {
  int levels = 0;
  const std::vector<int> level_of = ScaleLevels(base, obs, &levels);
  report->scale_temperature_levels = levels;
  const int max_order = std::min(kMaxThermalOrder, levels - 2);
  if (max_order < 1) return 0;
  // The gyro's sensitivity tempco is quadratic in temperature (physics.md: regressors w*dT and
  // w*dT^2); held-out error only decides whether a cubic is wanted. Leaving out an end level
  // extrapolates, which penalises the quadratic against a line even where the line misses the
  // curvature by several hundred ppm at the range's ends and middle.
  const int min_order = base.gyro() ? std::min(kGyroMinScaleOrder, max_order) : 0;
  report->scale_min_order = min_order;
  double best = std::numeric_limits<double>::infinity();
  int best_order = min_order;
  std::vector<std::optional<double>> scores(static_cast<size_t>(min_order));  // not tried
  for (int order = min_order; order <= max_order; ++order) {
    ChannelModel m = base;
    m.scale_order = order;
    double sum = 0.0;
    int tested = 0;
    for (int level = 0; level < levels; ++level) {
      std::vector<size_t> train, test;
      for (size_t i = 0; i < obs.size(); ++i) (level_of[i] == level ? test : train).push_back(i);
      sum += HeldOutSquares(serial, m, obs, train, test, n_thermal, options, bias_cnt2, wander);
      tested += static_cast<int>(test.size());
    }
    const double score = std::sqrt(sum / std::max(tested, 1));
    scores.push_back(score);
    if (score < best) {
      best = score;
      best_order = order;
    }
  }
  report->scale_held_out_normalised_rms_by_order = scores;
  return best_order;
}

bool HasFormat3Terms(const std::array<ChannelModel, 9>& models) {
  for (const ChannelModel& m : models) {
    if (m.scale_order > 0 || m.quadratic || m.g_sensitivity) return true;
  }
  return false;
}

}  // namespace adahrs::calib::joint_fit
