// What an ADS fit reports beside its constants, per surface (altitude, airspeed): the points and
// terms it used and its residual at them; per strategy, the tolerance ratios at the points, the
// hysteresis half loops and spans the centre fit separated, and the bridge linearisation. Written
// into constants.json's `diagnostics` (docs/constants-file.md); read back typed (FromJson) with
// the file, never into a calibration. Units are in the key names: ft, kt or pa (a pressure
// surface), c (degrees Celsius).
#pragma once

#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace adahrs::calib {

struct HysteresisSpanDiagnostics {
  double pressure_span_pa = 0.0;
  double pressure_span_se_pa = 0.0;
  double thermal_span_c = 0.0;
  double thermal_span_se_c = 0.0;
  double weighted_cost_at_nominal_spans = 0.0;
  double weighted_cost = 0.0;
  bool at_search_edge = false;
  nlohmann::json ToJson() const;
};

/// The centre fit's half loops, Pa per unit state (c = -FS h / 2 for a loop of h FSO).
struct SurfaceHysteresisDiagnostics {
  double pressure_half_loop_pa = 0.0;
  double pressure_half_loop_se_pa = 0.0;
  double thermal_half_loop_pa = 0.0;
  double thermal_half_loop_se_pa = 0.0;
  std::optional<double> pressure_half_loop_pa_per_c;  ///< strategies with temperature slopes
  std::optional<double> thermal_half_loop_pa_per_c;
  double centre_fit_residual_rms_pa = 0.0;
  std::optional<double> die_temperature_residual_rms_c;
  nlohmann::json ToJson() const;
};

struct BridgeLinearisationDiagnostics {
  double curvature_per_code = 0.0;
  double curvature_se_per_code = 0.0;
  double slope_cnt_per_c = 0.0;
  double quadratic_residual_rms_c = 0.0;
  nlohmann::json ToJson() const;
};

struct AdsSurfaceDiagnostics {
  std::string unit;  ///< of the residuals: "ft", "kt" or "pa"
  int points = 0;
  int terms = 0;
  int y_degree = 0;
  int dof = 0;
  double residual_rms = 0.0;
  double max_abs_residual = 0.0;
  std::optional<double> worst_ratio_at_points_weighted_fit;  ///< minimax strategies
  std::optional<double> worst_ratio_at_points;
  std::optional<int> lawson_iterations;
  std::map<int, double> held_out_worst_ratio_by_y_degree;  ///< empty: no degree search
  std::optional<SurfaceHysteresisDiagnostics> hysteresis;
  std::optional<BridgeLinearisationDiagnostics> bridge_linearisation;
  std::optional<HysteresisSpanDiagnostics> hysteresis_spans;
  std::string law;  ///< empty: the surface is the output itself
  nlohmann::json ToJson() const;
};

struct AdsFitDiagnostics {
  AdsSurfaceDiagnostics altitude_ft;
  AdsSurfaceDiagnostics airspeed_kt;
  nlohmann::json ToJson() const;
  /// Reads ToJson's object back; refuses a wrong type, a missing or an unknown key with
  /// ConstantsFileError naming `source` and the JSON path. Null numbers are read as NaN.
  static AdsFitDiagnostics FromJson(const nlohmann::json& j,
                                    const std::string& source,
                                    const std::string& path = "$.diagnostics");
};

}  // namespace adahrs::calib
