// The joint IMU fit's model, one linear model per channel (docs/calibration-strategies.md): the
// terms of a channel (offset, thermal polynomial in tau = (TEMP count - 32768) / 4096, the stimulus
// 3-vector f_B in g or w_B in deg/s, gyro w^2 and w^3, and the format-3 terms), each observation's
// design row and white-noise variance (measured, or the datasheet's for the bound), the weighted
// solve with the gyro bias wander, and the held-out choice of the thermal and scale-factor orders.
// The residual of the Ceres split: imu_joint_mapping.h maps solved models to firmware numbers,
// imu_constant_vector.h orders those numbers, imu_joint_fit.cc runs the fit.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "calib/imu_calibration/imu_joint_fit.h"
#include "calib/imu_calibration/imu_observations.h"
#include "calib/solvers/linear_least_squares.h"
#include "common/imu_layout.h"
#include "firmware_model/unit_firmware.h"

namespace adahrs::calib::joint_fit {

namespace fm = firmware_model;

static_assert(kMaxThermalOrder == fm::kImuThermalDegree);

inline constexpr std::array<int, 6> kAxisOfChannel = {2, 0, 1, 2, 0, 1};
inline constexpr int kPairOfAxis[3][2] = {{1, 4}, {2, 5}, {0, 3}};
// Temperature counts are fitted in tau = (t - centre) / span (conditioning), re-expanded in Map.
inline constexpr double kTempCentre_cnt = 32768.0;
inline constexpr double kTempSpan_cnt = 4096.0;
inline constexpr double kInverseCubicSpan_dps = 150.0;  // the gyro's rated range (ADXRS150)
inline constexpr double kDScale_cnt = 3.0e6;  // ~ counts at 150 deg/s, conditions the cubic

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

// How the bias wander enters a fit: not at all (accelerometers, projections of a true unit), as
// each observation's own extra variance (order selection: cheap, ignores the correlation), or with
// its covariance between observations (generalised least squares: the fit and the bound).
enum class BiasWander { kNone, kDiagonal, kCorrelated };

// The stimulus along the channel's own axis: f_axis in g, or the rate about the gyro's axis.
double OwnStimulus(const ChannelModel& m, const ImuObservation& o);

// What the scale terms multiply: the own stimulus, a gyro's through its nonlinearity.
double ScaledStimulus(const ChannelModel& m, const ImuObservation& o);

// Mean of tau^p over an observation's rows from its raw temperature moments E[t^i]:
// E[((t - c)/s)^p] = sum_i C(p, i) E[t^i] (-c)^(p - i) / s^p.
double TauPowerMean(const ImuObservation& o, int sensor, int p);

Eigen::RowVectorXd DesignRow(const ChannelModel& m, const ImuObservation& o);

std::vector<std::string> TermNames(const ChannelModel& m);

double MedianThermalCount(const std::vector<ImuObservation>& obs);

// Variance of an observation's mean from white noise: measured (fit weights) or datasheet (CRB).
// The gyro bias wander is not in it: it correlates observations (gyro_bias_covariance.h).
double Variance(const ImuObservation& o,
                int ch,
                double n_thermal,
                bool datasheet,
                const ImuDatasheetNoise& noise);

LinearFit Solve(const std::string& serial,
                ChannelModel& m,
                const std::vector<ImuObservation>& obs,
                const std::vector<size_t>& use,
                double n_thermal,
                bool datasheet,
                const ImuJointOptions& options,
                const Eigen::MatrixXd& bias_cnt2,
                BiasWander wander,
                double model_variance = 0.0);

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
                      BiasWander wander);

// 5-fold held-out error over the thermal bands for each order; the order with the least.
int ChooseOrder(const std::string& serial,
                int ch,
                const std::vector<ImuObservation>& obs,
                double n_thermal,
                const ImuJointOptions& options,
                const Eigen::MatrixXd& bias_cnt2,
                BiasWander wander,
                JointChannelDiagnostics* report);

std::vector<int> ScaleLevels(const ChannelModel& m,
                             const std::vector<ImuObservation>& obs,
                             int* level_count);

int ChooseScaleOrder(const std::string& serial,
                     const ChannelModel& base,
                     const std::vector<ImuObservation>& obs,
                     double n_thermal,
                     const ImuJointOptions& options,
                     const Eigen::MatrixXd& bias_cnt2,
                     BiasWander wander,
                     JointChannelDiagnostics* report);

bool HasFormat3Terms(const std::array<ChannelModel, 9>& models);

}  // namespace adahrs::calib::joint_fit
