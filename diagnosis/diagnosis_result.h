// What a diagnosis says of one unit (docs/diagnose.md "diagnosis.json"): the effects found with
// their components and standard errors in physical units, the structure no candidate explains, the
// smallest size each untested or absent effect would have been found at, and each channel's fit.
// The IMU diagnosis (imu_diagnosis.h) and the ADS one (ads_diagnosis.h) both fill it; ToJson is
// the diagnosis.json schema.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace adahrs::diagnosis {

struct FindingComponent {
  std::string name;  ///< "delay", "x", "tc1", ...
  double magnitude = 0.0;
  double standard_error = 0.0;
  std::string unit;  ///< "s", "mg", "deg/s", "degC", "ppm/degC", "ppm/degC^2", "mg/g^2", "deg/s/g"
  nlohmann::json ToJson() const;
};

struct Finding {
  std::string effect;   ///< vocabulary of docs/diagnose.md
  std::string channel;  ///< az1 ... gz
  std::vector<FindingComponent> components;
  std::optional<double> time_constant_s;  ///< self_heating_warm_up's chosen tau_w
  double wald_p_value = 0.0;
  double held_out_rms_before = 0.0;  ///< the final model without this term, channel unit
  double held_out_rms_after = 0.0;   ///< the final model
  std::string rms_unit;
  std::vector<std::string> evidence;  ///< segments where the term contributes most
  std::string words;
  nlohmann::json ToJson() const;
};

struct Unexplained {
  std::string channel;
  std::string where;
  std::string description;
  double size = 0.0;
  std::string unit;
  nlohmann::json ToJson() const;
};

struct DetectionLimit {
  std::string effect;
  std::string channel;
  std::vector<FindingComponent> limits;  ///< magnitude = smallest detectable; empty when untestable
  std::string note;                      ///< why it cannot be tested, when it cannot
  nlohmann::json ToJson() const;
};

struct ChannelFitSummary {
  std::string channel;
  std::string unit;
  double held_out_rms_baseline = 0.0;
  double held_out_rms_final = 0.0;
  double white_noise_rms = 0.0;  ///< what white noise alone would leave in a cell mean, median
  std::vector<std::string> baseline_terms;
  /// The bias's slope against temperature under a linear law (offset + slope per degC, the
  /// reference inputs' terms as in the baseline) and its jackknife standard error, unit per degC;
  /// filled by the generic channel diagnosis where the temperatures tell it.
  std::optional<double> bias_slope_per_c, bias_slope_se_per_c;
  /// What one residual value is the mean of: a 1 s cell of rows (IMU, channel CSVs), or an ADS
  /// calibration point (a step's rows), which the report's figure says.
  enum class Residuals { kPerCell, kPerCalibrationPoint } residuals = Residuals::kPerCell;
  /// For the report's figures (not in ToJson): cell times, thermometer temperature and the
  /// residual of the baseline and of the final model, channel unit, at most kPlotCells cells.
  std::vector<double> plot_t_s, plot_temp_c, plot_residual_baseline, plot_residual_final;
  nlohmann::json ToJson() const;
};

inline constexpr int kPlotCells = 1500;

struct UnitDiagnosis {
  std::string serial;
  int rows = 0;
  int segments = 0;
  int cells = 0;
  double temp_span_c = 0.0;
  bool thermometers_fitted = false;
  int tests = 0;            ///< (channel, candidate) tests the Bonferroni level divides by
  double test_alpha = 0.0;  ///< per test
  std::vector<Finding> findings;
  std::vector<Unexplained> unexplained;
  std::vector<DetectionLimit> detection_limits;
  std::vector<ChannelFitSummary> channels;
  std::vector<std::string> notes;
  /// True only with no finding and nothing unexplained (a held-out error far above the noise is
  /// unexplained, held_out_excess.h): only then may a report say "no missing physics found".
  bool NoMissingPhysics() const { return findings.empty() && unexplained.empty(); }
  /// The one-line verdict the CLI, report.html and diagnosis.json's `verdict` share.
  std::string Verdict() const;
  nlohmann::json ToJson() const;
};

}  // namespace adahrs::diagnosis
