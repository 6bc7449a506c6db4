#include "diagnosis/diagnosis_result.h"

namespace adahrs::diagnosis {

using nlohmann::json;

json FindingComponent::ToJson() const {
  return {
      {"name", name}, {"magnitude", magnitude}, {"standard_error", standard_error}, {"unit", unit}};
}

json Finding::ToJson() const {
  json comps = json::array();
  for (const FindingComponent& c : components) comps.push_back(c.ToJson());
  json j = {{"effect", effect},
            {"channels", json::array({channel})},
            {"components", comps},
            {"wald_p_value", wald_p_value},
            {"held_out_rms_before", held_out_rms_before},
            {"held_out_rms_after", held_out_rms_after},
            {"rms_unit", rms_unit},
            {"evidence", evidence},
            {"words", words}};
  if (!components.empty()) {
    j["magnitude"] = components[0].magnitude;
    j["standard_error"] = components[0].standard_error;
    j["unit"] = components[0].unit;
  }
  if (time_constant_s) j["time_constant_s"] = *time_constant_s;
  return j;
}

json Unexplained::ToJson() const {
  return {{"channel", channel},
          {"where", where},
          {"description", description},
          {"size", size},
          {"unit", unit}};
}

json DetectionLimit::ToJson() const {
  json j = {{"effect", effect}, {"channel", channel}};
  if (limits.empty()) {
    j["limits"] = nullptr;
    j["note"] = note;
  } else {
    json l = json::array();
    for (const FindingComponent& c : limits)
      l.push_back({{"name", c.name}, {"smallest_detectable", c.magnitude}, {"unit", c.unit}});
    j["limits"] = l;
  }
  return j;
}

json ChannelFitSummary::ToJson() const {
  json j = {{"channel", channel},
            {"unit", unit},
            {"held_out_rms_baseline", held_out_rms_baseline},
            {"held_out_rms_final", held_out_rms_final},
            {"white_noise_rms_per_cell", white_noise_rms},
            {"baseline_terms", baseline_terms}};
  if (bias_slope_per_c) {
    j["bias_slope_per_degc"] = {{"value", *bias_slope_per_c},
                                {"standard_error", bias_slope_se_per_c.value_or(0.0)},
                                {"unit", unit + "/degC"},
                                {"law", "linear in temperature"}};
  }
  return j;
}

std::string UnitDiagnosis::Verdict() const {
  if (NoMissingPhysics()) return "no missing physics found";
  if (unexplained.empty()) return "missing physics found";
  if (findings.empty())
    return "no candidate term found, but the model does not explain this recording (unexplained)";
  return "missing physics found, and the model still does not explain all of this recording "
         "(unexplained)";
}

json UnitDiagnosis::ToJson() const {
  json f = json::array(), u = json::array(), d = json::array(), c = json::array();
  for (const Finding& x : findings) f.push_back(x.ToJson());
  for (const Unexplained& x : unexplained) u.push_back(x.ToJson());
  for (const DetectionLimit& x : detection_limits) d.push_back(x.ToJson());
  for (const ChannelFitSummary& x : channels) c.push_back(x.ToJson());
  return {{"serial", serial},
          {"rows", rows},
          {"segments", segments},
          {"cells", cells},
          {"temperature_span_c", temp_span_c},
          {"thermometers_fitted", thermometers_fitted},
          {"tests", tests},
          {"per_test_alpha", test_alpha},
          {"verdict", Verdict()},
          {"findings", f},
          {"unexplained", u},
          {"detection_limits", d},
          {"channels", c},
          {"notes", notes}};
}

}  // namespace adahrs::diagnosis
