#include "proving/evaluation/imu_evaluation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "calib/acceptance/acceptance_judge.h"
#include "calib/constants/imu_fit_diagnostics.h"
#include "calib/imu_calibration/imu_joint_fit.h"
#include "calib/imu_calibration/imu_observations.h"
#include "common/units.h"
#include "firmware_model/constants_exporter.h"
#include "firmware_model/reference_compensator.h"
#include "firmware_model/unit_firmware.h"
#include "proving/evaluation/simulated_raw_frame.h"

namespace adahrs::proving {
namespace {

namespace fm = firmware_model;
using nlohmann::json;

constexpr double kTempMin_c = -40.0, kTempMax_c = 85.0, kTempStep_c = 12.5;
constexpr double kRates_dps[] = {-150, -100, -50, 50, 100, 150};
constexpr double kSigmaLimit = 3.0;  // CRB limit per point: 3 sigma
constexpr double kCrbMargin = 1.5;   // within 1.5x the CRB-implied limit
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

sensor_sim::ImuUnitParams NoiseOff(sensor_sim::ImuUnitParams p) {
  for (auto& chip : p.accel_chips) chip.effects.noise = false;
  for (auto& g : p.gyros) {
    g.effects.noise = false;
    g.effects.bias_instability = false;
    g.effects.rate_random_walk = false;
  }
  for (auto& t : p.accel_thermal) t.effects.lag = false;
  for (auto& t : p.gyro_thermal) t.effects.lag = false;
  return p;
}

// Standard deviation of the six outputs at `raw` implied by `cov` of the firmware numbers.
std::array<double, 6> OutputSigma(const fm::ImuCalibrationConstants& c,
                                  const Eigen::MatrixXd& cov,
                                  const fm::ImuRawFrame& raw) {
  const Eigen::VectorXd v = calib::FlattenConstants(c);
  Eigen::MatrixXd jac(6, calib::kImuFirmwareNumbers);
  for (int j = 0; j < calib::kImuFirmwareNumbers; ++j) {
    const double h =
        std::max(1e-3 * std::sqrt(std::max(cov(j, j), 0.0)), 1e-14 * std::max(1.0, std::abs(v[j])));
    Eigen::VectorXd plus = v, minus = v;
    plus[j] += h;
    minus[j] -= h;
    const auto a = fm::ImuReference(
        calib::UnflattenConstants(plus, c), fm::ImuCompensationMode::kFullyCalibrated, raw);
    const auto b = fm::ImuReference(
        calib::UnflattenConstants(minus, c), fm::ImuCompensationMode::kFullyCalibrated, raw);
    for (int i = 0; i < 6; ++i) jac(i, j) = (a[i] - b[i]) / (2.0 * h);
  }
  const Eigen::MatrixXd out = jac * cov * jac.transpose();
  std::array<double, 6> sigma{};
  for (int i = 0; i < 6; ++i) sigma[i] = std::sqrt(std::max(out(i, i), 0.0));
  return sigma;
}

struct GridPoint {
  double temp_c = 0.0;
  int orientation = 0;
  double rate_dps = 0.0;
  Eigen::Vector3d up = Eigen::Vector3d::Zero();
  std::vector<fm::ImuRawFrame> frames;
};

// The noise-free unit at every grid point: `frames` frames after settling.
std::vector<GridPoint> SimulateGrid(const sensor_sim::ImuUnitParams& params,
                                    double g_l,
                                    const ImuEvaluationOptions& options) {
  std::vector<GridPoint> grid;
  for (double temp_c = kTempMin_c; temp_c <= kTempMax_c + 1e-9; temp_c += kTempStep_c) {
    sensor_sim::ImuUnit unit(params, options.seed, temp_c);
    std::vector<std::pair<int, double>> points;
    for (int o : {11, 12, 21, 22, 31, 32}) points.push_back({o, 0.0});
    for (int o : {11, 21, 31}) {
      for (double r : kRates_dps) points.push_back({o, r});
    }
    for (const auto& [orientation, rate_dps] : points) {
      GridPoint p;
      p.temp_c = temp_c;
      p.orientation = orientation;
      p.rate_dps = rate_dps;
      const auto up = calib::UpAxisOf(orientation);
      p.up = Eigen::Vector3d(up[0], up[1], up[2]);
      sensor_sim::ImuStimulus s;
      s.f_B_g = g_l * p.up;
      s.w_B_dps = rate_dps * p.up;
      s.air_temp_c = temp_c;
      for (int i = 0; i < options.settle_frames; ++i) unit.Step(s);
      for (int i = 0; i < options.frames; ++i) p.frames.push_back(ToFirmwareRawFrame(unit.Step(s)));
      grid.push_back(std::move(p));
    }
  }
  return grid;
}

// Mean fixed-point outputs minus truth at every grid point: A in m/s^2 (slots 0..2), G in deg/s
// (slots 3..5).
std::vector<std::array<double, 6>> GridErrors(const fm::ImuCalibrationConstants& c,
                                              const std::vector<GridPoint>& grid,
                                              double g_local_mps2) {
  const fm::ImuExport exported = fm::ExportImuConstants(c);
  std::vector<std::array<double, 6>> out;
  for (const GridPoint& p : grid) {
    std::array<double, 6> sum{};
    for (const fm::ImuRawFrame& f : p.frames) {
      fm::DspEngine engine(fm::CompensatorDspConfig());
      fm::ImuCompensatedFrame frame{};
      fm::ImuCompensate(
          &engine, exported.constants, fm::ImuCompensationMode::kFullyCalibrated, f, &frame);
      const auto v = fm::ImuFrameToDouble(fm::ImuCompensationMode::kFullyCalibrated, frame);
      for (int k = 0; k < 6; ++k) sum[k] += v[k];
    }
    std::array<double, 6> err{};
    const double n = static_cast<double>(p.frames.size());
    for (int k = 0; k < 3; ++k) {
      err[k] = sum[k] / n - g_local_mps2 * p.up[k];
      err[3 + k] = sum[3 + k] / n - p.rate_dps * p.up[k];
    }
    out.push_back(err);
  }
  return out;
}

// The true unit projected onto the firmware's model (the joint model fitted to the noise-free
// grid, thermal order 3, equal weights; with the format-3 terms, scale order 3, when `format3`):
// the best constants the structure can hold. No die-lag terms: the grid's TEMP counts are steady,
// and the rounding residue of their slope would be fitted as a regressor.
fm::ImuCalibrationConstants TruthProjection(const std::string& serial,
                                            const std::vector<GridPoint>& grid,
                                            double g_l,
                                            bool format3) {
  std::vector<calib::ImuObservation> observations;
  for (const GridPoint& p : grid) {
    calib::ObservationBuilder builder;
    for (size_t i = 0; i < p.frames.size(); ++i)
      builder.Add(p.frames[i], static_cast<double>(i) * 0.01);
    observations.push_back(builder.Finish("grid", false, 0, g_l * p.up, p.rate_dps * p.up));
  }
  calib::ImuJointOptions options;
  options.thermal_order = calib::kMaxThermalOrder;
  options.unit_weights = true;
  options.format3 = format3;
  options.scale_order = calib::kMaxThermalOrder;
  options.die_lag_terms = false;
  return calib::FitImuJoint(serial + " (truth projection)", observations, options).constants;
}

// The projection's errors at every grid point (the firmware floor). The projection can need a
// thermal block the exporter cannot hold: then the floor is unknown (NaN everywhere).
std::vector<std::array<double, 6>> FloorErrors(const fm::ImuCalibrationConstants& projection,
                                               const std::vector<GridPoint>& grid,
                                               double g_local_mps2) {
  try {
    return GridErrors(projection, grid, g_local_mps2);
  } catch (const std::invalid_argument&) {
    return std::vector<std::array<double, 6>>(grid.size(), {kNaN, kNaN, kNaN, kNaN, kNaN, kNaN});
  }
}

// mg per m/s^2 (acceleration errors at rest).
constexpr double kMgPerMps2 = 1e3 / common::kStandardGravity_mps2;

struct QuantitySummary {
  double worst = 0.0;
  double worst_floor = 0.0;
  double max_crb_limit = 0.0;
  double worst_crb_limit = 0.0;
  bool all_in_spec = true;
  bool all_in_crb = true;
  json worst_point;
};

std::string Verdict(const QuantitySummary& q, bool have_crb) {
  if (q.all_in_spec) return calib::PointVerdictText(calib::PointVerdict::kWithinSpecification);
  // No CRB covariance (the reference strategy): no limit to judge against.
  if (!have_crb) return calib::PointVerdictText(calib::PointVerdict::kOutsideSpecification);
  if (q.all_in_crb) return "outside specification, within 1.5x the physical limit";
  if (q.worst <= kCrbMargin * (q.worst_floor + q.max_crb_limit)) {
    return "outside specification, within 1.5x the firmware floor plus the physical limit";
  }
  return calib::PointVerdictText(calib::PointVerdict::kOutsideBoth);
}

// The CRB covariance of the constants' numbers (none when the file carries none: the reference
// strategy); files written before format 3 carry the format-2 numbers' covariance only. A null
// (not finite) entry counts as zero.
std::optional<Eigen::MatrixXd> CrbCovariance(const calib::ConstantsFile& file) {
  if (!file.imu_diagnostics || !file.imu_diagnostics->joint) return std::nullopt;
  const std::vector<std::vector<double>>& rows = file.imu_diagnostics->joint->crb_covariance;
  constexpr int n = calib::kImuFirmwareNumbers;
  const int size =
      rows.size() == static_cast<size_t>(calib::kImuFormat2Numbers) ? calib::kImuFormat2Numbers : n;
  if (rows.size() != static_cast<size_t>(size)) {
    throw std::invalid_argument(file.serial + ": $.diagnostics.crb_covariance is not " +
                                std::to_string(n) + "x" + std::to_string(n) + " (or " +
                                std::to_string(calib::kImuFormat2Numbers) + " square, format 2)");
  }
  Eigen::MatrixXd crb = Eigen::MatrixXd::Zero(n, n);
  for (int r = 0; r < size; ++r) {
    if (rows[r].size() != static_cast<size_t>(size)) {
      throw std::invalid_argument(file.serial + ": $.diagnostics.crb_covariance[" +
                                  std::to_string(r) + "] is not " + std::to_string(size) + " long");
    }
    for (int k = 0; k < size; ++k) crb(r, k) = std::isfinite(rows[r][k]) ? rows[r][k] : 0.0;
  }
  return crb;
}

// Every grid point's errors against the specification, the firmware floor and the CRB limit,
// summarised per quantity (acceleration at rest, body rate on the table).
struct GridJudgement {
  QuantitySummary accel, rate;
  json points = json::array();
};

GridJudgement JudgeGrid(const fm::ImuCalibrationConstants& c,
                        const std::vector<GridPoint>& grid,
                        const std::vector<std::array<double, 6>>& errors,
                        const std::vector<std::array<double, 6>>& floor,
                        const Eigen::MatrixXd* crb,
                        const calib::Specification& spec) {
  static constexpr const char* kAxis[] = {"x", "y", "z"};
  GridJudgement out;
  for (size_t i = 0; i < grid.size(); ++i) {
    const GridPoint& p = grid[i];
    const std::array<double, 6> sigma =
        crb ? OutputSigma(c, *crb, p.frames.back()) : std::array<double, 6>{};
    json point = {{"temp_c", p.temp_c}, {"orientation", p.orientation}, {"rate_dps", p.rate_dps}};
    for (int k = 0; k < 3; ++k) {
      const bool at_rest = p.rate_dps == 0.0;
      const int slot = at_rest ? k : 3 + k;
      const double to_unit = at_rest ? kMgPerMps2 : 1.0;  // mg or deg/s
      const double err = errors[i][slot] * to_unit;
      const double fl = floor[i][slot] * to_unit;
      const double lim = kSigmaLimit * sigma[slot] * to_unit;
      QuantitySummary& q = at_rest ? out.accel : out.rate;
      const double tol = at_rest ? spec.accel_mg : spec.body_rate_dps;
      const bool in_spec = std::abs(err) <= tol;
      q.all_in_spec &= in_spec;
      q.all_in_crb &= in_spec || std::abs(err) <= kCrbMargin * lim;
      q.max_crb_limit = std::max(q.max_crb_limit, lim);
      q.worst_floor = std::isnan(fl) || std::isnan(q.worst_floor)
                          ? kNaN
                          : std::max(q.worst_floor, std::abs(fl));
      if (std::abs(err) > q.worst) {
        q.worst = std::abs(err);
        q.worst_crb_limit = lim;
        q.worst_point = point;
        q.worst_point["axis"] = kAxis[k];
        q.worst_point["firmware_floor"] = fl;
      }
      const std::string unit = at_rest ? "_mg_" : "_dps_";
      point[std::string("error") + unit + kAxis[k]] = err;
      point[std::string("firmware_floor") + unit + kAxis[k]] = fl;
      point[std::string("crb_limit") + unit + kAxis[k]] = lim;
    }
    out.points.push_back(point);
  }
  return out;
}

// Each constant against the projection of the true unit, in its standard errors and CRB ones.
struct ParameterComparison {
  json parameters = json::array();
  json summary;
};

ParameterComparison CompareParameters(const calib::ConstantsFile& file,
                                      const fm::ImuCalibrationConstants& projection,
                                      const Eigen::MatrixXd* crb) {
  const Eigen::VectorXd value = calib::FlattenConstants(*file.imu);
  const Eigen::VectorXd true_value = calib::FlattenConstants(projection);
  const std::vector<std::string> names = calib::ConstantNames();
  const Eigen::VectorXd se = calib::FlattenConstants(calib::ImuStandardErrors(file));
  ParameterComparison out;
  double sum_se = 0.0, sum_crb = 0.0;
  int n_se = 0, n_crb = 0;
  for (int i = 0; i < calib::kImuFirmwareNumbers; ++i) {
    const double err = value[i] - true_value[i];
    const double crb_se = crb ? std::sqrt(std::max((*crb)(i, i), 0.0)) : 0.0;
    json p = {{"name", names[i]},
              {"value", value[i]},
              {"truth_projection", true_value[i]},
              {"error", err}};
    if (std::isfinite(se[i]) && se[i] > 0.0) {
      p["standard_error"] = se[i];
      p["error_over_se"] = err / se[i];
      sum_se += err * err / (se[i] * se[i]);
      ++n_se;
    }
    if (crb_se > 0.0 && std::isfinite(se[i])) {
      p["crb_se"] = crb_se;
      p["error_over_crb"] = err / crb_se;
      sum_crb += err * err / (crb_se * crb_se);
      ++n_crb;
    }
    out.parameters.push_back(p);
  }
  out.summary = {{"rms_error_over_se", n_se ? std::sqrt(sum_se / n_se) : 0.0},
                 {"rms_error_over_crb", n_crb ? std::sqrt(sum_crb / n_crb) : 0.0},
                 {"compared_with_se", n_se},
                 {"compared_with_crb", n_crb}};
  return out;
}

json QuantityReport(const QuantitySummary& q,
                    const char* unit,
                    double spec,
                    const std::string& verdict) {
  const std::string u(unit);
  return {{"worst_error_" + u, q.worst},
          {"spec_" + u, spec},
          {"crb_limit_" + u + "_at_worst", q.worst_crb_limit},
          {"worst_firmware_floor_" + u, q.worst_floor},
          {"worst_point", q.worst_point},
          {"verdict", verdict}};
}

}  // namespace

ImuEvaluation EvaluateImu(const calib::ConstantsFile& file,
                          const sensor_sim::ImuUnitParams& truth,
                          const calib::Specification& spec,
                          const ImuEvaluationOptions& options) {
  if (file.kind != hil::UnitKind::kImu || !file.imu) {
    throw std::invalid_argument("evaluate: constants of " + file.serial + " are not an IMU's");
  }
  const fm::ImuCalibrationConstants& c = *file.imu;
  const std::optional<Eigen::MatrixXd> crb = CrbCovariance(file);
  const double g_l = common::Mps2ToG(options.g_local_mps2);
  const std::vector<GridPoint> grid = SimulateGrid(NoiseOff(truth), g_l, options);
  // Format-3 constants are judged against the best format-3 constants.
  const fm::ImuCalibrationConstants projection =
      TruthProjection(file.serial, grid, g_l, c.scale_temperature.active);
  std::vector<std::array<double, 6>> errors;
  try {
    errors = GridErrors(c, grid, options.g_local_mps2);
  } catch (const std::invalid_argument& e) {
    throw ConstantsNotExportable("evaluate: constants of " + file.serial +
                                 " cannot be exported to the firmware: " + e.what());
  }
  const std::vector<std::array<double, 6>> floor =
      FloorErrors(projection, grid, options.g_local_mps2);
  const GridJudgement judged = JudgeGrid(c, grid, errors, floor, crb ? &*crb : nullptr, spec);
  const ParameterComparison parameters = CompareParameters(file, projection, crb ? &*crb : nullptr);

  ImuEvaluation e;
  e.worst_accel_mg = judged.accel.worst;
  e.worst_rate_dps = judged.rate.worst;
  e.accel_verdict = Verdict(judged.accel, crb.has_value());
  e.rate_verdict = Verdict(judged.rate, crb.has_value());
  e.report = {
      {"format", "adahrs-imu-evaluation"},
      {"format_version", 1},
      {"serial", file.serial},
      {"strategy", file.strategy},
      {"specification", spec.ToJson()},
      {"grid",
       {{"temp_c", {kTempMin_c, kTempMax_c, kTempStep_c}},
        {"rates_dps", kRates_dps},
        {"frames_per_point", options.frames},
        {"switched_off",
         "accelerometer and gyro noise, gyro bias instability and rate random walk, die lag"}}},
      {"acceleration", QuantityReport(judged.accel, "mg", spec.accel_mg, e.accel_verdict)},
      {"body_rate", QuantityReport(judged.rate, "dps", spec.body_rate_dps, e.rate_verdict)},
      {"parameters", parameters.parameters},
      {"parameter_summary", parameters.summary},
      {"points", judged.points}};
  return e;
}

ImuFirmwareFloor EvaluateImuFirmwareFloor(const sensor_sim::ImuUnitParams& truth,
                                          bool format3,
                                          const ImuEvaluationOptions& options) {
  const double g_l = common::Mps2ToG(options.g_local_mps2);
  const std::vector<GridPoint> grid = SimulateGrid(NoiseOff(truth), g_l, options);
  const std::vector<std::array<double, 6>> floor =
      FloorErrors(TruthProjection(truth.serial, grid, g_l, format3), grid, options.g_local_mps2);
  ImuFirmwareFloor out;
  for (size_t i = 0; i < grid.size(); ++i) {
    const bool at_rest = grid[i].rate_dps == 0.0;
    double& worst = at_rest ? out.worst_accel_mg : out.worst_rate_dps;
    for (int k = 0; k < 3; ++k) {
      const double fl = at_rest ? floor[i][k] * kMgPerMps2 : floor[i][3 + k];
      worst = std::isnan(fl) || std::isnan(worst) ? kNaN : std::max(worst, std::abs(fl));
    }
  }
  return out;
}

}  // namespace adahrs::proving
