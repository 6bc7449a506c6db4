#include "calib/constants/ads_fit_diagnostics.h"

namespace adahrs::calib {

using nlohmann::json;

json HysteresisSpanDiagnostics::ToJson() const {
  return {{"pressure_span_pa", pressure_span_pa},
          {"pressure_span_se_pa", pressure_span_se_pa},
          {"thermal_span_c", thermal_span_c},
          {"thermal_span_se_c", thermal_span_se_c},
          {"weighted_cost_at_nominal_spans", weighted_cost_at_nominal_spans},
          {"weighted_cost", weighted_cost},
          {"at_search_edge", at_search_edge}};
}

json SurfaceHysteresisDiagnostics::ToJson() const {
  json j = {{"pressure_half_loop_pa", pressure_half_loop_pa},
            {"pressure_half_loop_se_pa", pressure_half_loop_se_pa},
            {"thermal_half_loop_pa", thermal_half_loop_pa},
            {"thermal_half_loop_se_pa", thermal_half_loop_se_pa},
            {"centre_fit_residual_rms_pa", centre_fit_residual_rms_pa}};
  if (pressure_half_loop_pa_per_c) j["pressure_half_loop_pa_per_c"] = *pressure_half_loop_pa_per_c;
  if (thermal_half_loop_pa_per_c) j["thermal_half_loop_pa_per_c"] = *thermal_half_loop_pa_per_c;
  if (die_temperature_residual_rms_c)
    j["die_temperature_residual_rms_c"] = *die_temperature_residual_rms_c;
  return j;
}

json BridgeLinearisationDiagnostics::ToJson() const {
  return {{"curvature_per_code", curvature_per_code},
          {"curvature_se_per_code", curvature_se_per_code},
          {"slope_cnt_per_c", slope_cnt_per_c},
          {"quadratic_residual_rms_c", quadratic_residual_rms_c}};
}

json AdsSurfaceDiagnostics::ToJson() const {
  json j = {{"points", points},
            {"terms", terms},
            {"y_degree", y_degree},
            {"dof", dof},
            {"residual_rms_" + unit, residual_rms},
            {"max_abs_residual_" + unit, max_abs_residual}};
  if (worst_ratio_at_points_weighted_fit)
    j["worst_ratio_at_points_weighted_fit"] = *worst_ratio_at_points_weighted_fit;
  if (worst_ratio_at_points) j["worst_ratio_at_points"] = *worst_ratio_at_points;
  if (lawson_iterations) j["lawson_iterations"] = *lawson_iterations;
  if (!held_out_worst_ratio_by_y_degree.empty()) {
    json by_degree = json::object();
    for (const auto& [degree, ratio] : held_out_worst_ratio_by_y_degree)
      by_degree[std::to_string(degree)] = ratio;
    j["held_out_worst_ratio_by_y_degree"] = by_degree;
  }
  if (hysteresis) j["hysteresis"] = hysteresis->ToJson();
  if (bridge_linearisation) j["bridge_linearisation"] = bridge_linearisation->ToJson();
  if (hysteresis_spans) j["hysteresis_spans"] = hysteresis_spans->ToJson();
  if (!law.empty()) j["law"] = law;
  return j;
}

json AdsFitDiagnostics::ToJson() const {
  return {{"altitude_ft", altitude_ft.ToJson()}, {"airspeed_kt", airspeed_kt.ToJson()}};
}

}  // namespace adahrs::calib
