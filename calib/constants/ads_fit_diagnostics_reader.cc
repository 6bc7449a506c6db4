// AdsFitDiagnostics::FromJson: the diagnostics section of an ADS constants.json read back
// strictly, the inverse of the ToJson functions in ads_fit_diagnostics.cc.
#include <string>

#include "calib/constants/ads_fit_diagnostics.h"
#include "calib/constants/diagnostics_reader.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;
using Reader = DiagnosticsReader;

HysteresisSpanDiagnostics ReadSpans(const Reader& r) {
  HysteresisSpanDiagnostics d;
  d.pressure_span_pa = r.Number("pressure_span_pa");
  d.pressure_span_se_pa = r.Number("pressure_span_se_pa");
  d.thermal_span_c = r.Number("thermal_span_c");
  d.thermal_span_se_c = r.Number("thermal_span_se_c");
  d.weighted_cost_at_nominal_spans = r.Number("weighted_cost_at_nominal_spans");
  d.weighted_cost = r.Number("weighted_cost");
  d.at_search_edge = r.Flag("at_search_edge");
  r.ExpectAllKeysUsed();
  return d;
}

SurfaceHysteresisDiagnostics ReadHysteresis(const Reader& r) {
  SurfaceHysteresisDiagnostics d;
  d.pressure_half_loop_pa = r.Number("pressure_half_loop_pa");
  d.pressure_half_loop_se_pa = r.Number("pressure_half_loop_se_pa");
  d.thermal_half_loop_pa = r.Number("thermal_half_loop_pa");
  d.thermal_half_loop_se_pa = r.Number("thermal_half_loop_se_pa");
  d.centre_fit_residual_rms_pa = r.Number("centre_fit_residual_rms_pa");
  if (r.Has("pressure_half_loop_pa_per_c"))
    d.pressure_half_loop_pa_per_c = r.Number("pressure_half_loop_pa_per_c");
  if (r.Has("thermal_half_loop_pa_per_c"))
    d.thermal_half_loop_pa_per_c = r.Number("thermal_half_loop_pa_per_c");
  if (r.Has("die_temperature_residual_rms_c"))
    d.die_temperature_residual_rms_c = r.Number("die_temperature_residual_rms_c");
  r.ExpectAllKeysUsed();
  return d;
}

BridgeLinearisationDiagnostics ReadLinearisation(const Reader& r) {
  BridgeLinearisationDiagnostics d;
  d.curvature_per_code = r.Number("curvature_per_code");
  d.curvature_se_per_code = r.Number("curvature_se_per_code");
  d.slope_cnt_per_c = r.Number("slope_cnt_per_c");
  d.quadratic_residual_rms_c = r.Number("quadratic_residual_rms_c");
  r.ExpectAllKeysUsed();
  return d;
}

// The unit of a surface's residuals is in its keys (residual_rms_ft, _kt or _pa).
std::string ResidualUnit(const Reader& r) {
  for (const char* unit : {"ft", "kt", "pa"}) {
    if (r.Has(std::string("residual_rms_") + unit)) return unit;
  }
  r.Fail(r.PathOf("residual_rms_ft"), "missing key (nor residual_rms_kt or residual_rms_pa)");
}

std::map<int, double> ReadByDegree(const Reader& r) {
  std::map<int, double> out;
  const Reader by = r.Child("held_out_worst_ratio_by_y_degree");
  for (const std::string& key : by.Keys()) {
    if (key.empty() || key.size() > 2 || key.find_first_not_of("0123456789") != std::string::npos)
      by.Fail(by.PathOf(key), "not a degree (0 to 99)");
    out[std::stoi(key)] = by.Number(key);
  }
  return out;
}

AdsSurfaceDiagnostics ReadSurface(const Reader& r) {
  AdsSurfaceDiagnostics d;
  d.unit = ResidualUnit(r);
  d.points = r.Int("points");
  d.terms = r.Int("terms");
  d.y_degree = r.Int("y_degree");
  d.dof = r.Int("dof");
  d.residual_rms = r.Number("residual_rms_" + d.unit);
  d.max_abs_residual = r.Number("max_abs_residual_" + d.unit);
  if (r.Has("worst_ratio_at_points_weighted_fit"))
    d.worst_ratio_at_points_weighted_fit = r.Number("worst_ratio_at_points_weighted_fit");
  if (r.Has("worst_ratio_at_points")) d.worst_ratio_at_points = r.Number("worst_ratio_at_points");
  if (r.Has("lawson_iterations")) d.lawson_iterations = r.Int("lawson_iterations");
  if (r.Has("held_out_worst_ratio_by_y_degree"))
    d.held_out_worst_ratio_by_y_degree = ReadByDegree(r);
  if (r.Has("hysteresis")) d.hysteresis = ReadHysteresis(r.Child("hysteresis"));
  if (r.Has("bridge_linearisation"))
    d.bridge_linearisation = ReadLinearisation(r.Child("bridge_linearisation"));
  if (r.Has("hysteresis_spans")) d.hysteresis_spans = ReadSpans(r.Child("hysteresis_spans"));
  if (r.Has("law")) d.law = r.String("law");
  r.ExpectAllKeysUsed();
  return d;
}

}  // namespace

AdsFitDiagnostics AdsFitDiagnostics::FromJson(const json& j,
                                              const std::string& source,
                                              const std::string& path) {
  const Reader r(j, source, path);
  AdsFitDiagnostics d;
  d.altitude_ft = ReadSurface(r.Child("altitude_ft"));
  d.airspeed_kt = ReadSurface(r.Child("airspeed_kt"));
  r.ExpectAllKeysUsed();
  return d;
}

}  // namespace adahrs::calib
