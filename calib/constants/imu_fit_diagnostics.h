// What an IMU fit reports beside its constants: for the reference strategy each stage's numbers
// (thermal drift per channel with its ramp hysteresis, six-position inverse scales, gyro cubics,
// cross-axis conditioning); for the joint strategy each channel's chosen orders, held-out scores,
// bias wander and residuals, and the Cramér–Rao bound of the firmware numbers; for both the rows
// the fit left out and the local gravity it used. Written into constants.json's `diagnostics`
// (docs/constants-file.md) by ToJson; FromJson reads that section back, refusing a wrong type, a
// missing or an unknown key with the source and JSON path. The evaluation reads the bound and the
// local gravity back; nothing feeds a calibration. Units are in the key names in lower case (cnt,
// dps, dph, mps2, ppm_per_c, g_per_duty); "U units" are a channel's raw output (duty or counts).
// Numbers that came out NaN are written null (constants_file.h) and read back as NaN.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace adahrs::calib {

/// Reference strategy, stage 1: one channel's quadratic drift in its TEMP count.
struct ThermalChannelDiagnostics {
  int bands = 0;
  int samples = 0;
  double residual_rms = 0.0;  ///< U units
  double temp_min_cnt = 0.0;
  double temp_max_cnt = 0.0;
  double hysteresis = 0.0;  ///< largest |up − down| over the common range, U units
  double hysteresis_at_temp_cnt = 0.0;
  std::optional<std::array<double, 3>> up_ramp_k;  ///< up-ramp rows alone, U units per count^i
  std::optional<std::array<double, 3>> down_ramp_k;
  std::string ramp_note;  ///< why a ramp is absent; empty when both are fitted
};

/// Reference strategy, stage 2: one accelerometer's inverse scale (g per duty).
struct AccelScaleDiagnostics {
  std::string channel;
  double inverse_scale_g_per_duty = 0.0;
  double inverse_scale_se_g_per_duty = 0.0;
};

/// Reference strategy, stage 3: one gyro's cubic over the rate steps about its axis.
struct GyroScaleDiagnostics {
  std::string channel;
  int rates = 0;
  double residual_rms_dps = 0.0;
};

/// Reference strategy, stage 4.
struct CrossAxisDiagnostics {
  std::string source;  ///< "cross_axis step" or "accel and gyro steps"
  double ca_condition = 0.0;
  double cg_condition = 0.0;
};

struct ReferenceFitDiagnostics {
  std::string strategy_steps;
  std::map<std::string, ThermalChannelDiagnostics> thermal;  ///< by channel name (az1 ... gz)
  std::vector<AccelScaleDiagnostics> accel;                  ///< az1 ... ay2
  std::vector<GyroScaleDiagnostics> gyro;                    ///< gx, gy, gz
  CrossAxisDiagnostics cross_axis;
};

/// Joint strategy: a gyro's bias wander, the datasheet prior or estimated (gyro_wander_fit.h).
struct BiasWanderDiagnostics {
  double floor_dph = 0.0;
  double time_scale = 1.0;
  std::optional<double> white_variance_scale;  ///< estimated only (as the three below)
  std::optional<double> log_likelihood_gain_over_datasheet;
  std::optional<bool> at_grid_edge;
  std::string source;
};

/// Joint strategy: one channel's fit (imu_joint_fit.h).
struct JointChannelDiagnostics {
  /// Thermal orders 0...3 by 5-fold held-out error; empty when the order was not chosen.
  std::vector<double> held_out_normalised_rms_by_order;
  std::optional<int> scale_temperature_levels;  ///< format 3, scale order chosen
  std::optional<int> scale_min_order;           ///< format 3, with at least 3 levels
  /// Scale orders 0...; nullopt below the smallest tried; empty when the order was not chosen.
  std::vector<std::optional<double>> scale_held_out_normalised_rms_by_order;
  std::optional<int> scale_order;                    ///< format 3
  std::optional<BiasWanderDiagnostics> bias_wander;  ///< gyros, weighted fits
  double model_error_rms = 0.0;                      ///< U units
  int thermal_order = 0;
  int observations = 0;
  double residual_rms = 0.0;  ///< U units
  double sigma_ratio_to_datasheet = 0.0;
  std::optional<double> scale_tempco_ppm_per_c;  ///< format 2, accelerometers
  std::optional<double> scale_tempco_se_ppm_per_c;
  std::string scale_tempco_note;  ///< format 2, accelerometers; empty otherwise
};

struct JointFitDiagnostics {
  std::map<std::string, JointChannelDiagnostics> channels;  ///< by channel name (az1 ... gz)
  int64_t observations = 0;
  std::vector<std::string> crb_parameters;  ///< the firmware numbers' names (ConstantNames)
  /// Cramér–Rao bound of the firmware numbers, rows in crb_parameters' order.
  std::vector<std::vector<double>> crb_covariance;
  std::string firmware_cannot_hold;
};

struct ImuFitDiagnostics {
  std::optional<ReferenceFitDiagnostics> reference;  ///< set by FitImuReference
  std::optional<JointFitDiagnostics> joint;          ///< set by FitImuJoint
  std::optional<int64_t> excluded_rows;              ///< set by FitImuReference and FitImuUnit
  std::vector<std::string> exclusions;  ///< the first 100 excluded rows (reference strategy)
  std::optional<int64_t> rejected_interval_rows;
  std::optional<double> local_gravity_mps2;  ///< set by FitImuUnit

  nlohmann::json ToJson() const;
  /// `source` names the file (or unit) in messages; `path` is where `j` sits in it.
  static ImuFitDiagnostics FromJson(const nlohmann::json& j,
                                    const std::string& source,
                                    const std::string& path = "$.diagnostics");
};

}  // namespace adahrs::calib
