#include "calib/imu_calibration/imu_joint_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "calib/imu_calibration/gyro_bias_covariance.h"
#include "calib/imu_calibration/gyro_wander_fit.h"
#include "calib/imu_calibration/imu_constant_vector.h"
#include "calib/imu_calibration/imu_joint_mapping.h"
#include "calib/imu_calibration/imu_joint_model.h"
#include "calib/imu_calibration/imu_reference_fit.h"
#include "calib/solvers/linear_least_squares.h"
#include "common/imu_layout.h"
#include "common/units.h"
#include "firmware_model/unit_firmware.h"

namespace adahrs::calib {
namespace {

using namespace joint_fit;  // NOLINT(google-build-using-namespace): this fit's model and mapping

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
