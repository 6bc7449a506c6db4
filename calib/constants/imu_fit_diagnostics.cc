#include "calib/constants/imu_fit_diagnostics.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;

json ToJson(const ThermalChannelDiagnostics& d) {
  json j = {{"bands", d.bands},
            {"samples", d.samples},
            {"residual_rms", d.residual_rms},
            {"temp_min_cnt", d.temp_min_cnt},
            {"temp_max_cnt", d.temp_max_cnt},
            {"hysteresis", d.hysteresis},
            {"hysteresis_at_temp_cnt", d.hysteresis_at_temp_cnt}};
  if (d.up_ramp_k) j["up_ramp_k"] = *d.up_ramp_k;
  if (d.down_ramp_k) j["down_ramp_k"] = *d.down_ramp_k;
  if (!d.ramp_note.empty()) j["ramp_note"] = d.ramp_note;
  return j;
}

void AddReference(const ReferenceFitDiagnostics& d, json* j) {
  json thermal = json::object();
  for (const auto& [channel, t] : d.thermal) thermal[channel] = ToJson(t);
  json accel = json::array();
  for (const AccelScaleDiagnostics& a : d.accel) {
    accel.push_back({{"channel", a.channel},
                     {"inverse_scale_g_per_duty", a.inverse_scale_g_per_duty},
                     {"inverse_scale_se_g_per_duty", a.inverse_scale_se_g_per_duty}});
  }
  json gyro = json::array();
  for (const GyroScaleDiagnostics& g : d.gyro) {
    gyro.push_back(
        {{"channel", g.channel}, {"rates", g.rates}, {"residual_rms_dps", g.residual_rms_dps}});
  }
  (*j)["strategy_steps"] = d.strategy_steps;
  (*j)["thermal"] = thermal;
  (*j)["accel"] = accel;
  (*j)["gyro"] = gyro;
  (*j)["cross_axis"] = {{"source", d.cross_axis.source},
                        {"ca_condition", d.cross_axis.ca_condition},
                        {"cg_condition", d.cross_axis.cg_condition}};
}

json ToJson(const BiasWanderDiagnostics& w) {
  json j = {{"floor_dph", w.floor_dph}, {"time_scale", w.time_scale}, {"source", w.source}};
  if (w.white_variance_scale) j["white_variance_scale"] = *w.white_variance_scale;
  if (w.log_likelihood_gain_over_datasheet)
    j["log_likelihood_gain_over_datasheet"] = *w.log_likelihood_gain_over_datasheet;
  if (w.at_grid_edge) j["at_grid_edge"] = *w.at_grid_edge;
  return j;
}

json ToJson(const JointChannelDiagnostics& c) {
  json j = {{"model_error_rms", c.model_error_rms},
            {"thermal_order", c.thermal_order},
            {"observations", c.observations},
            {"residual_rms", c.residual_rms},
            {"sigma_ratio_to_datasheet", c.sigma_ratio_to_datasheet}};
  if (!c.held_out_normalised_rms_by_order.empty())
    j["held_out_normalised_rms_by_order"] = c.held_out_normalised_rms_by_order;
  if (c.scale_temperature_levels) j["scale_temperature_levels"] = *c.scale_temperature_levels;
  if (c.scale_min_order) j["scale_min_order"] = *c.scale_min_order;
  if (!c.scale_held_out_normalised_rms_by_order.empty()) {
    json scores = json::array();
    for (const std::optional<double>& s : c.scale_held_out_normalised_rms_by_order) {
      scores.push_back(s ? json(*s) : json(nullptr));  // null: order not tried
    }
    j["scale_held_out_normalised_rms_by_order"] = scores;
  }
  if (c.scale_order) j["scale_order"] = *c.scale_order;
  if (c.bias_wander) j["bias_wander"] = ToJson(*c.bias_wander);
  if (c.scale_tempco_ppm_per_c) j["scale_tempco_ppm_per_c"] = *c.scale_tempco_ppm_per_c;
  if (c.scale_tempco_se_ppm_per_c) j["scale_tempco_se_ppm_per_c"] = *c.scale_tempco_se_ppm_per_c;
  if (!c.scale_tempco_note.empty()) j["scale_tempco_note"] = c.scale_tempco_note;
  return j;
}

void AddJoint(const JointFitDiagnostics& d, json* j) {
  json channels = json::object();
  for (const auto& [name, c] : d.channels) channels[name] = ToJson(c);
  (*j)["channels"] = channels;
  (*j)["observations"] = d.observations;
  (*j)["crb_parameters"] = d.crb_parameters;
  (*j)["crb_covariance"] = d.crb_covariance;
  (*j)["firmware_cannot_hold"] = d.firmware_cannot_hold;
}

}  // namespace

json ImuFitDiagnostics::ToJson() const {
  json j = json::object();
  if (reference) AddReference(*reference, &j);
  if (joint) AddJoint(*joint, &j);
  if (excluded_rows) j["excluded_rows"] = *excluded_rows;
  if (!exclusions.empty()) j["exclusions"] = exclusions;
  if (rejected_interval_rows) j["rejected_interval_rows"] = *rejected_interval_rows;
  if (local_gravity_mps2) j["local_gravity_mps2"] = *local_gravity_mps2;
  return j;
}

}  // namespace adahrs::calib
