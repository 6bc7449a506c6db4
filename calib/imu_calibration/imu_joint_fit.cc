#include "calib/imu_calibration/imu_joint_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "calib/imu_calibration/gyro_bias_covariance.h"
#include "calib/imu_calibration/gyro_wander_fit.h"
#include "calib/imu_calibration/imu_reference_fit.h"
#include "calib/solvers/linear_least_squares.h"
#include "common/imu_layout.h"
#include "common/median.h"
#include "common/units.h"
#include "firmware_model/unit_firmware.h"

namespace adahrs::calib {
namespace {

namespace fm = firmware_model;

static_assert(kMaxThermalOrder == fm::kImuThermalDegree);

constexpr std::array<int, 6> kAxisOfChannel = {2, 0, 1, 2, 0, 1};
constexpr int kPairOfAxis[3][2] = {{1, 4}, {2, 5}, {0, 3}};
// Temperature counts are fitted in tau = (t - centre) / span (conditioning), re-expanded in Map.
constexpr double kTempCentre_cnt = 32768.0;
constexpr double kTempSpan_cnt = 4096.0;
constexpr double kInverseCubicSpan_dps = 150.0;  // the gyro's rated range (ADXRS150)
constexpr double kDScale_cnt = 3.0e6;            // ~ counts at 150 deg/s, conditions the cubic

// One channel's linear model and its fit.
// Terms: offset, tau^1..order, the stimulus 3-vector (f_B or w_B), gyro w^2 and w^3, then the
// format-3 terms: tau^p times the channel's own stimulus (p = 1..scale_order; a gyro's with its
// nonlinearity, w + (q2 w^2 + q3 w^3) / S from a provisional fit, as the sensitivity tempco scales
// the whole response and the firmware's F scales the count before the cubic), the accelerometer's
// f_axis^2, the gyro's f_x, f_y, f_z (g-sensitivity).
struct ChannelModel {
  int channel = 0;
  int order = 2;
  int scale_order = 0;
  bool quadratic = false;
  bool g_sensitivity = false;
  bool lag = false;  // accelerometer: tau_dot and tau_dot tau (die lag behind the thermometer)
  double nl2_per_dps = 0.0;   // gyro: q2 / S and q3 / S of a provisional fit (the scale terms'
  double nl3_per_dps2 = 0.0;  // stimulus is w + nl2 w^2 + nl3 w^3)

  bool gyro() const { return channel >= 6; }
  int sensor() const { return common::kImuChannels[channel].thermometer; }
  int stimulus_index() const { return 1 + order; }
  int scale_index() const { return stimulus_index() + (gyro() ? 5 : 3); }
  int extra_index() const { return scale_index() + scale_order; }
  int lag_index() const { return extra_index() + (quadratic ? 1 : 0) + (g_sensitivity ? 3 : 0); }
  int size() const { return lag_index() + (lag ? 2 : 0); }
};

// The stimulus along the channel's own axis: f_axis in g, or the rate about the gyro's axis.
double OwnStimulus(const ChannelModel& m, const ImuObservation& o) {
  return m.gyro() ? o.w_B_dps[m.channel - 6] : o.f_B_g[kAxisOfChannel[m.channel]];
}

// What the scale terms multiply: the own stimulus, a gyro's through its nonlinearity.
double ScaledStimulus(const ChannelModel& m, const ImuObservation& o) {
  const double s = OwnStimulus(m, o);
  return m.gyro() ? s + m.nl2_per_dps * s * s + m.nl3_per_dps2 * s * s * s : s;
}

// Mean of tau^p over an observation's rows from its raw temperature moments E[t^i]:
// E[((t - c)/s)^p] = sum_i C(p, i) E[t^i] (-c)^(p - i) / s^p.
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

// Variance of an observation's mean from white noise: measured (fit weights) or datasheet (CRB).
// The gyro bias wander is not in it: it correlates observations (gyro_bias_covariance.h).
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

// How the bias wander enters a fit: not at all (accelerometers, projections of a true unit), as
// each observation's own extra variance (order selection: cheap, ignores the correlation), or with
// its covariance between observations (generalised least squares: the fit and the bound).
enum class BiasWander { kNone, kDiagonal, kCorrelated };

LinearFit Solve(const std::string& serial,
                ChannelModel& m,
                const std::vector<ImuObservation>& obs,
                const std::vector<size_t>& use,
                double n_thermal,
                bool datasheet,
                const ImuJointOptions& options,
                const Eigen::MatrixXd& bias_cnt2,
                BiasWander wander,
                double model_variance = 0.0) {
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

// Sum over `test` of the squared residuals of `m` fitted to `train`, each over its observation's
// variance (white noise, plus the bias wander unless `wander` is kNone).
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

// 5-fold held-out error over the thermal bands for each order; the order with the least.
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

// F_c(t) = 1 / (1 + delta_c(tau) / S_c) as a least-squares cubic in (t - origin) over the
// sensor's span, delta_c = sum_p theta_p tau^p and S_c the channel's own stimulus coefficient.
std::array<double, 4> ScaleFactorCubic(const ChannelModel& m,
                                       const Eigen::VectorXd& theta,
                                       double own_scale,
                                       const fm::TempSensorSpan& span) {
  constexpr int kPoints = 41;
  Eigen::MatrixXd a(kPoints, 4);
  Eigen::VectorXd f(kPoints);
  const double half = std::max(span.origin_cnt - span.min_cnt, span.max_cnt - span.origin_cnt);
  for (int i = 0; i < kPoints; ++i) {
    const double t = span.min_cnt + (span.max_cnt - span.min_cnt) * i / (kPoints - 1);
    const double tau = (t - kTempCentre_cnt) / kTempSpan_cnt;
    double delta = 0.0;
    for (int p = m.scale_order; p >= 1; --p) delta = (delta + theta[m.scale_index() + p - 1]) * tau;
    const double x = (t - span.origin_cnt) / half;
    a.row(i) << 1.0, x, x * x, x * x * x;
    f[i] = 1.0 / (1.0 + delta / own_scale);
  }
  const Eigen::Vector4d b = a.colPivHouseholderQr().solve(f);
  return {b[0], b[1] / half, b[2] / (half * half), b[3] / (half * half * half)};
}

// The format-3 terms (calibration_constants.h ImuScaleTemperature): the scale factors, q_axis =
// -(k2_i / S_i + k2_j / S_j) / 2 (the pair mean's f^2 coefficient, removed), and GS = -CG
// diag(1 / n_gg) Gsens / g0 (Gsens in counts per g, A = g0 f).
void MapScaleTemperature(const std::array<ChannelModel, 9>& models,
                         const std::array<Eigen::VectorXd, 9>& theta,
                         const std::array<std::array<double, 2>, 3>& temp_span_cnt,
                         const Eigen::Matrix3d& cg,
                         fm::ImuCalibrationConstants* c) {
  fm::ImuScaleTemperature& st = c->scale_temperature;
  st.active = true;
  for (int s = 0; s < 3; ++s) {
    const double lo = temp_span_cnt[s][0], hi = temp_span_cnt[s][1];
    st.sensor[s] = {std::nearbyint(0.5 * (lo + hi)), lo, hi};
  }
  std::array<double, 9> own{};
  for (int ch = 0; ch < 9; ++ch) {
    const ChannelModel& m = models[ch];
    own[ch] = theta[ch][m.stimulus_index() + (m.gyro() ? ch - 6 : kAxisOfChannel[ch])];
    st.scale[ch] = ScaleFactorCubic(m, theta[ch], own[ch], st.sensor[m.sensor()]);
  }
  for (int axis = 0; axis < 3; ++axis) {
    double q = 0.0;
    for (int ch : kPairOfAxis[axis]) {
      if (models[ch].quadratic) q -= 0.5 * theta[ch][models[ch].extra_index()] / own[ch];
    }
    st.accel_quadratic_per_g[axis] = q;
  }
  Eigen::Matrix3d gsens_dps_per_g = Eigen::Matrix3d::Zero();
  for (int g = 0; g < 3; ++g) {
    const ChannelModel& m = models[6 + g];
    if (!m.g_sensitivity) continue;
    for (int a = 0; a < 3; ++a)
      gsens_dps_per_g(g, a) = theta[6 + g][m.extra_index() + a] / own[6 + g];
  }
  const Eigen::Matrix3d gs = -cg * gsens_dps_per_g / common::kStandardGravity_mps2;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) st.gs_dps_per_mps2[r][k] = gs(r, k);
  }
}

// The channel models -> the firmware numbers (the mapping of the header comment); each
// channel's thermal span is `temp_span_cnt[sensor]`.
fm::ImuCalibrationConstants Map(const std::array<ChannelModel, 9>& models,
                                const std::array<Eigen::VectorXd, 9>& theta,
                                const std::array<std::array<double, 2>, 3>& temp_span_cnt) {
  fm::ImuCalibrationConstants c;
  const double tc = kTempCentre_cnt, ts = kTempSpan_cnt;
  // xi(t) = sum_{j>=1} alpha_j tau^j, tau = (t - tc)/ts, re-expanded in raw counts by Horner's
  // rule on polynomials in t: k <- k * (t - tc)/ts + alpha_j for j = order ... 0 (alpha_0 = 0:
  // the offset is the channel's o_i or null, not part of xi).
  auto thermal = [&](int ch, double* offset) {
    const ChannelModel& m = models[ch];
    const Eigen::VectorXd& th = theta[ch];
    std::array<double, kMaxThermalOrder + 1> k{};  // k[i]: coefficient of t^i
    for (int j = m.order; j >= 0; --j) {
      for (int i = kMaxThermalOrder; i >= 1; --i) k[i] = (k[i - 1] - tc * k[i]) / ts;
      k[0] = -tc * k[0] / ts + (j >= 1 ? th[j] : 0.0);
    }
    c.thermal[ch].temp_sensor = m.sensor();
    c.thermal[ch].k = k;
    c.thermal[ch].temp_min_cnt = temp_span_cnt[m.sensor()][0];
    c.thermal[ch].temp_max_cnt = temp_span_cnt[m.sensor()][1];
    *offset = th[0];
  };
  std::array<Eigen::Vector3d, 6> m_over_s;
  for (int ch = 0; ch < 6; ++ch) {
    double offset = 0.0;
    thermal(ch, &offset);
    const int k = 1 + models[ch].order;
    const Eigen::Vector3d m(theta[ch][k], theta[ch][k + 1], theta[ch][k + 2]);
    const double s = m[kAxisOfChannel[ch]];
    c.accel[ch] = {offset, s};
    m_over_s[ch] = m / s;
  }
  Eigen::Matrix3d pair;
  for (int axis = 0; axis < 3; ++axis) {
    pair.row(axis) =
        0.5 * (m_over_s[kPairOfAxis[axis][0]] + m_over_s[kPairOfAxis[axis][1]]).transpose();
  }
  const Eigen::Matrix3d ca = common::kStandardGravity_mps2 * pair.inverse();
  Eigen::Matrix3d n_rows;
  for (int g = 0; g < 3; ++g) {
    const int ch = 6 + g;
    double null_cnt = 0.0;
    thermal(ch, &null_cnt);
    const int k = 1 + models[ch].order;
    const Eigen::Vector3d n(theta[ch][k], theta[ch][k + 1], theta[ch][k + 2]);
    const double q2 = theta[ch][k + 3], q3 = theta[ch][k + 4];
    // l: least squares of w on x = d / kDScale over the rated span.
    constexpr int kRates = 61;
    Eigen::MatrixXd a(kRates, 3);
    Eigen::VectorXd w(kRates);
    for (int i = 0; i < kRates; ++i) {
      const double rate = -kInverseCubicSpan_dps + 2.0 * kInverseCubicSpan_dps * i / (kRates - 1);
      const double x = (n[g] * rate + q2 * rate * rate + q3 * rate * rate * rate) / kDScale_cnt;
      a.row(i) << x, x * x, x * x * x;
      w[i] = rate;
    }
    const Eigen::Vector3d lambda = a.colPivHouseholderQr().solve(w);
    c.gyro[g] = {null_cnt,
                 {0.0,
                  lambda[0] / kDScale_cnt,
                  lambda[1] / (kDScale_cnt * kDScale_cnt),
                  lambda[2] / (kDScale_cnt * kDScale_cnt * kDScale_cnt)}};
    n_rows.row(g) = n.transpose() / n[g];
  }
  const Eigen::Matrix3d cg = n_rows.inverse();
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      c.ca_mps2_per_g[r][k] = ca(r, k);
      c.cg[r][k] = cg(r, k);
    }
  }
  if (HasFormat3Terms(models)) MapScaleTemperature(models, theta, temp_span_cnt, cg, &c);
  return c;
}

// Cov of the firmware numbers from per-channel covariances through the mapping's Jacobian.
Eigen::MatrixXd Propagate(const std::array<ChannelModel, 9>& models,
                          const std::array<Eigen::VectorXd, 9>& theta,
                          const std::array<Eigen::MatrixXd, 9>& cov,
                          const std::array<std::array<double, 2>, 3>& temp_span_cnt) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(kImuFirmwareNumbers, kImuFirmwareNumbers);
  for (int ch = 0; ch < 9; ++ch) {
    const long p = theta[ch].size();
    Eigen::MatrixXd jac(kImuFirmwareNumbers, p);
    for (long j = 0; j < p; ++j) {
      const double h = std::max(1e-3 * std::sqrt(std::max(cov[ch](j, j), 0.0)),
                                1e-12 * std::max(1.0, std::abs(theta[ch][j])));
      std::array<Eigen::VectorXd, 9> plus = theta, minus = theta;
      plus[ch][j] += h;
      minus[ch][j] -= h;
      jac.col(j) = (FlattenConstants(Map(models, plus, temp_span_cnt)) -
                    FlattenConstants(Map(models, minus, temp_span_cnt))) /
                   (2.0 * h);
    }
    out += jac * cov[ch] * jac.transpose();
  }
  return out;
}

// The gyro channel's wander from the recording: its model's design over every observation, and
// the observations' own variances (gyro_wander_fit.h).
GyroWanderEstimate EstimateWander(const ChannelModel& m,
                                  const std::vector<ImuObservation>& obs,
                                  double n_thermal,
                                  const ImuJointOptions& options) {
  const long n = static_cast<long>(obs.size());
  Eigen::MatrixXd design(n, m.size());
  Eigen::VectorXd y(n), white(n);
  for (long r = 0; r < n; ++r) {
    const ImuObservation& o = obs[static_cast<size_t>(r)];
    design.row(r) = DesignRow(m, o);
    y[r] = o.u_mean[m.channel];
    white[r] = Variance(o, m.channel, n_thermal, false, options.noise);
  }
  return EstimateGyroWander(obs,
                            design,
                            y,
                            white,
                            options.noise.gyro_bias_floor_dph,
                            options.noise.gyro_cnt_per_dps,
                            options.noise.frame_period_s);
}

}  // namespace

Eigen::VectorXd FlattenConstants(const fm::ImuCalibrationConstants& c) {
  Eigen::VectorXd v(kImuFirmwareNumbers);
  int k = 0;
  for (const auto& t : c.thermal) {
    for (double x : t.k) v[k++] = x;
  }
  for (const auto& a : c.accel) {
    v[k++] = a.offset_duty;
    v[k++] = a.scale_duty_per_g;
  }
  for (const auto& g : c.gyro) {
    v[k++] = g.null_cnt;
    for (double x : g.l) v[k++] = x;
  }
  for (const auto& row : c.ca_mps2_per_g) {
    for (double x : row) v[k++] = x;
  }
  for (const auto& row : c.cg) {
    for (double x : row) v[k++] = x;
  }
  const fm::ImuScaleTemperature& st = c.scale_temperature;
  for (const auto& f : st.scale) {
    for (double x : f) v[k++] = st.active ? x : 0.0;
  }
  for (double q : st.accel_quadratic_per_g) v[k++] = st.active ? q : 0.0;
  for (const auto& row : st.gs_dps_per_mps2) {
    for (double x : row) v[k++] = st.active ? x : 0.0;
  }
  return v;
}

fm::ImuCalibrationConstants UnflattenConstants(const Eigen::VectorXd& v,
                                               const fm::ImuCalibrationConstants& like) {
  fm::ImuCalibrationConstants c = like;
  int k = 0;
  for (auto& t : c.thermal) {
    for (double& x : t.k) x = v[k++];
  }
  for (auto& a : c.accel) {
    a.offset_duty = v[k++];
    a.scale_duty_per_g = v[k++];
  }
  for (auto& g : c.gyro) {
    g.null_cnt = v[k++];
    for (double& x : g.l) x = v[k++];
  }
  for (auto& row : c.ca_mps2_per_g) {
    for (double& x : row) x = v[k++];
  }
  for (auto& row : c.cg) {
    for (double& x : row) x = v[k++];
  }
  fm::ImuScaleTemperature& st = c.scale_temperature;
  for (auto& f : st.scale) {
    for (double& x : f) x = v[k++];
  }
  for (double& q : st.accel_quadratic_per_g) q = v[k++];
  for (auto& row : st.gs_dps_per_mps2) {
    for (double& x : row) x = v[k++];
  }
  return c;
}

std::vector<std::string> ConstantNames() {
  std::vector<std::string> names;
  for (int ch = 0; ch < 9; ++ch) {
    for (int i = 0; i <= kMaxThermalOrder; ++i) {
      names.push_back("thermal[" + std::to_string(ch) + "].k[" + std::to_string(i) + "]");
    }
  }
  for (int ch = 0; ch < 6; ++ch) {
    names.push_back("accel[" + std::to_string(ch) + "].offset_duty");
    names.push_back("accel[" + std::to_string(ch) + "].scale_duty_per_g");
  }
  for (int g = 0; g < 3; ++g) {
    names.push_back("gyro[" + std::to_string(g) + "].null_cnt");
    for (int i = 0; i < 4; ++i) {
      names.push_back("gyro[" + std::to_string(g) + "].l[" + std::to_string(i) + "]");
    }
  }
  for (const char* m : {"ca_mps2_per_g", "cg"}) {
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) {
        names.push_back(std::string(m) + "[" + std::to_string(r) + "][" + std::to_string(k) + "]");
      }
    }
  }
  for (int ch = 0; ch < 9; ++ch) {
    for (int i = 0; i < 4; ++i) {
      names.push_back("scale_temperature.scale[" + std::to_string(ch) + "][" + std::to_string(i) +
                      "]");
    }
  }
  for (int a = 0; a < 3; ++a) {
    names.push_back("scale_temperature.accel_quadratic_per_g[" + std::to_string(a) + "]");
  }
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      names.push_back("scale_temperature.gs_dps_per_mps2[" + std::to_string(r) + "][" +
                      std::to_string(k) + "]");
    }
  }
  return names;
}

namespace {

// One channel's share of the fit: its model, estimate, covariances (the fit's and the bound's)
// and its diagnostics.
struct ChannelFit {
  ChannelModel model;
  Eigen::VectorXd theta;
  Eigen::MatrixXd cov;
  Eigen::MatrixXd crb;
  JointChannelDiagnostics report;
};

// Everything one channel's solves share.
struct ChannelContext {
  const std::string& serial;
  const std::vector<ImuObservation>& obs;
  const std::vector<size_t>& all;
  double n_thermal;
  const ImuJointOptions& options;
};

BiasWanderDiagnostics WanderReport(const std::optional<GyroWanderEstimate>& estimate,
                                   const ImuDatasheetNoise& noise) {
  if (!estimate) return {noise.gyro_bias_floor_dph, 1.0, {}, {}, {}, "datasheet prior"};
  return {estimate->floor_dph,
          estimate->time_scale,
          estimate->white_scale,
          estimate->log_likelihood_gain,
          estimate->at_grid_edge,
          "estimated from the recording (REML)"};
}

// Format 3: the scale factors' order in temperature, the accelerometer's f_axis^2, the gyro's
// g-sensitivity and the die-lag terms; a gyro's nonlinearity ratios from a provisional fit.
void ChooseFormat3Terms(const ChannelContext& cx,
                        const Eigen::MatrixXd& bias_cnt2,
                        BiasWander diagonal,
                        ChannelModel* m,
                        JointChannelDiagnostics* report) {
  m->quadratic = !m->gyro();
  m->g_sensitivity = m->gyro();
  m->lag = !m->gyro() && cx.options.die_lag_terms;
  m->scale_order =
      cx.options.scale_order
          ? *cx.options.scale_order
          : ChooseScaleOrder(
                cx.serial, *m, cx.obs, cx.n_thermal, cx.options, bias_cnt2, diagonal, report);
  report->scale_order = m->scale_order;
  if (m->gyro() && m->scale_order > 0) {
    const LinearFit provisional =
        Solve(cx.serial, *m, cx.obs, cx.all, cx.n_thermal, false, cx.options, bias_cnt2, diagonal);
    const double s_own = provisional.coefficients[m->stimulus_index() + m->channel - 6];
    m->nl2_per_dps = provisional.coefficients[m->stimulus_index() + 3] / s_own;
    m->nl3_per_dps2 = provisional.coefficients[m->stimulus_index() + 4] / s_own;
  }
}

// Model error (drift the thermal polynomial cannot follow) is shared by every observation: its
// variance, the thermal bands' mean squared residual beyond their noise, is added to every
// observation's variance and the fit repeated, so that the 25 degC acquisitions (tiny noise) do
// not pin the polynomial's misfit at 25 degC instead of spreading it over the range.
double ModelVariance(const ChannelContext& cx,
                     ChannelModel& m,
                     const Eigen::MatrixXd& bias_cnt2,
                     bool wanders,
                     BiasWander correlated) {
  const LinearFit first =
      Solve(cx.serial, m, cx.obs, cx.all, cx.n_thermal, false, cx.options, bias_cnt2, correlated);
  double excess = 0.0;
  int n_bands = 0;
  for (size_t i : cx.all) {
    const ImuObservation& o = cx.obs[i];
    if (!o.thermal) continue;
    const double r = o.u_mean[m.channel] - DesignRow(m, o).dot(first.coefficients);
    excess += r * r - Variance(o, m.channel, cx.n_thermal, false, cx.options.noise) -
              (wanders ? bias_cnt2(i, i) : 0.0);
    ++n_bands;
  }
  return cx.options.unit_weights || n_bands == 0 ? 0.0 : std::max(0.0, excess / n_bands);
}

// Format 2: the accelerometer's scale tempco that the firmware cannot hold, estimated for the
// record.
void ReportFormat2ScaleTempco(const ChannelContext& cx,
                              const ChannelModel& m,
                              const Eigen::MatrixXd& bias_cnt2,
                              JointChannelDiagnostics* report) {
  ChannelModel with = m;
  with.scale_order = 1;
  try {
    const LinearFit t = Solve(cx.serial,
                              with,
                              cx.obs,
                              cx.all,
                              cx.n_thermal,
                              false,
                              cx.options,
                              bias_cnt2,
                              BiasWander::kNone);
    const double s_axis = t.coefficients[with.stimulus_index() + kAxisOfChannel[m.channel]];
    // tau per degC: 110 counts per degC / 4096 counts per tau unit (thermal_drift_fit.h).
    const double per_c = 110.0 / kTempSpan_cnt / s_axis * 1e6;
    report->scale_tempco_ppm_per_c = t.coefficients[t.coefficients.size() - 1] * per_c;
    report->scale_tempco_se_ppm_per_c =
        t.standard_errors[t.standard_errors.size() - 1] * std::abs(per_c);
    report->scale_tempco_note =
        "estimated, not held by the firmware (no scale-vs-temperature term)";
  } catch (const DegenerateDesignError& e) {
    report->scale_tempco_note = std::string("not identifiable from this design: ") + e.what();
  }
}

ChannelFit FitChannel(const ChannelContext& cx, int ch, const Eigen::MatrixXd& prior_cnt2) {
  const ImuJointOptions& options = cx.options;
  ChannelFit out;
  ChannelModel& m = out.model;
  m.channel = ch;
  const bool wanders = ch >= 6 && !options.unit_weights;
  const BiasWander correlated = wanders ? BiasWander::kCorrelated : BiasWander::kNone;
  const BiasWander diagonal = wanders ? BiasWander::kDiagonal : BiasWander::kNone;
  m.order =
      options.thermal_order
          ? *options.thermal_order
          : ChooseOrder(
                cx.serial, ch, cx.obs, cx.n_thermal, options, prior_cnt2, diagonal, &out.report);
  // The gyro bias wander between observations: the datasheet's prior, or (if options say so)
  // each gyro's own, estimated from the recording (gyro_wander_fit.h).
  std::optional<GyroWanderEstimate> estimate;
  if (wanders && options.estimate_gyro_wander)
    estimate = EstimateWander(m, cx.obs, cx.n_thermal, options);
  if (wanders) out.report.bias_wander = WanderReport(estimate, options.noise);
  const Eigen::MatrixXd& bias_cnt2 = estimate ? estimate->covariance_cnt2 : prior_cnt2;
  if (estimate && !options.thermal_order) {
    m.order =
        ChooseOrder(cx.serial, ch, cx.obs, cx.n_thermal, options, bias_cnt2, diagonal, &out.report);
  }
  if (options.format3) ChooseFormat3Terms(cx, bias_cnt2, diagonal, &m, &out.report);
  const double model_variance = ModelVariance(cx, m, bias_cnt2, wanders, correlated);
  const LinearFit fit = Solve(cx.serial,
                              m,
                              cx.obs,
                              cx.all,
                              cx.n_thermal,
                              false,
                              options,
                              bias_cnt2,
                              correlated,
                              model_variance);
  out.report.model_error_rms = std::sqrt(model_variance);
  // The bound carries the same excess: scatter the datasheet's noise leaves out (rate random
  // walk, TEMP quantisation, drift between a level's visits) limits any estimator of this
  // design on this unit, and a bound without it is beaten by 5-80 standard errors.
  const LinearFit bound = Solve(cx.serial,
                                m,
                                cx.obs,
                                cx.all,
                                cx.n_thermal,
                                true,
                                options,
                                bias_cnt2,
                                correlated,
                                model_variance);
  out.theta = fit.coefficients;
  out.cov = fit.covariance;
  out.crb = bound.covariance;
  out.report.thermal_order = m.order;
  out.report.observations = fit.observations;
  out.report.residual_rms = fit.residual_rms;
  out.report.sigma_ratio_to_datasheet = fit.sigma;
  if (ch < 6 && !options.format3) ReportFormat2ScaleTempco(cx, m, bias_cnt2, &out.report);
  return out;
}

// The span each thermal polynomial is valid over: the observations' mean temperatures.
std::array<std::array<double, 2>, 3> TemperatureSpans(const std::string& serial,
                                                      const std::vector<ImuObservation>& obs) {
  std::array<std::array<double, 2>, 3> temp_span_cnt;
  for (int s = 0; s < 3; ++s) {
    temp_span_cnt[s] = {std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity()};
    for (const ImuObservation& o : obs) {
      temp_span_cnt[s][0] = std::min(temp_span_cnt[s][0], std::floor(o.t_mean_cnt[s]));
      temp_span_cnt[s][1] = std::max(temp_span_cnt[s][1], std::ceil(o.t_mean_cnt[s]));
    }
    if (!(temp_span_cnt[s][0] < temp_span_cnt[s][1])) {
      throw DegenerateDesignError("unit " + serial + ": TEMP sensor " + std::to_string(s) +
                                  " reads one temperature in every observation (" +
                                  std::to_string(temp_span_cnt[s][0]) +
                                  " counts): no thermal span to calibrate over");
    }
  }
  return temp_span_cnt;
}

std::vector<std::vector<double>> Rows(const Eigen::MatrixXd& m) {
  std::vector<std::vector<double>> rows(static_cast<size_t>(m.rows()),
                                        std::vector<double>(static_cast<size_t>(m.cols())));
  for (int r = 0; r < m.rows(); ++r) {
    for (int k = 0; k < m.cols(); ++k) rows[r][k] = m(r, k);
  }
  return rows;
}

}  // namespace

ImuFitResult FitImuJoint(const std::string& serial,
                         const std::vector<ImuObservation>& obs,
                         const ImuJointOptions& options) {
  std::vector<size_t> all(obs.size());
  for (size_t i = 0; i < obs.size(); ++i) all[i] = i;
  const ChannelContext cx{serial, obs, all, MedianThermalCount(obs), options};
  // The datasheet's gyro bias wander between observations, counts^2.
  const double cpd = options.noise.gyro_cnt_per_dps;
  const Eigen::MatrixXd prior_cnt2 =
      options.unit_weights
          ? Eigen::MatrixXd()
          : Eigen::MatrixXd(GyroBiasCovariance_dps2(obs,
                                                    options.noise.gyro_bias_floor_dph / 3600.0,
                                                    options.noise.frame_period_s) *
                            (cpd * cpd));
  std::array<ChannelModel, 9> models;
  std::array<Eigen::VectorXd, 9> theta;
  std::array<Eigen::MatrixXd, 9> cov, crb;
  JointFitDiagnostics diag;
  for (int ch = 0; ch < 9; ++ch) {
    ChannelFit f = FitChannel(cx, ch, prior_cnt2);
    models[ch] = f.model;
    theta[ch] = std::move(f.theta);
    cov[ch] = std::move(f.cov);
    crb[ch] = std::move(f.crb);
    diag.channels[common::kImuChannelNames[ch]] = std::move(f.report);
  }
  const std::array<std::array<double, 2>, 3> temp_span_cnt = TemperatureSpans(serial, obs);
  ImuFitResult result;
  result.constants = Map(models, theta, temp_span_cnt);
  const Eigen::MatrixXd cov_fw = Propagate(models, theta, cov, temp_span_cnt);
  const Eigen::MatrixXd crb_fw = Propagate(models, theta, crb, temp_span_cnt);
  Eigen::VectorXd se = cov_fw.diagonal().cwiseMax(0.0).cwiseSqrt();
  // l0 is fixed at zero by the mapping (the null holds the offset): not estimated.
  constexpr int kFirstGyroNumber = 9 * (kMaxThermalOrder + 1) + 6 * 2;
  for (int g = 0; g < 3; ++g) {
    se[kFirstGyroNumber + 5 * g + 1] = std::numeric_limits<double>::quiet_NaN();
  }
  result.standard_errors = UnflattenConstants(se, result.constants);
  diag.observations = static_cast<int64_t>(obs.size());
  diag.crb_parameters = ConstantNames();
  diag.crb_covariance = Rows(crb_fw);
  diag.firmware_cannot_hold =
      options.format3 ? "thermal and scale-factor orders above 3, the tempco of cross-axis terms"
                      : "accelerometer scale vs temperature, accelerometer nonlinearity, gyro "
                        "g-sensitivity, thermal orders above 3";
  result.diagnostics.joint = std::move(diag);
  return result;
}

}  // namespace adahrs::calib
