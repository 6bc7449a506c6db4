// ImuFitDiagnostics::FromJson: the diagnostics section of a constants.json read back strictly.
#include "calib/constants/diagnostics_reader.h"
#include "calib/constants/imu_fit_diagnostics.h"
#include "common/imu_layout.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;
using Reader = DiagnosticsReader;

std::array<double, 3> Three(const Reader& r, const std::string& key) {
  const std::vector<double> v = r.Numbers(key);
  if (v.size() != 3) r.Fail(r.PathOf(key), "expected 3 numbers");
  return {v[0], v[1], v[2]};
}

ThermalChannelDiagnostics ReadThermal(const Reader& r) {
  ThermalChannelDiagnostics d;
  d.bands = r.Int("bands");
  d.samples = r.Int("samples");
  d.residual_rms = r.Number("residual_rms");
  d.temp_min_cnt = r.Number("temp_min_cnt");
  d.temp_max_cnt = r.Number("temp_max_cnt");
  d.hysteresis = r.Number("hysteresis");
  d.hysteresis_at_temp_cnt = r.Number("hysteresis_at_temp_cnt");
  if (r.Has("up_ramp_k")) d.up_ramp_k = Three(r, "up_ramp_k");
  if (r.Has("down_ramp_k")) d.down_ramp_k = Three(r, "down_ramp_k");
  if (r.Has("ramp_note")) d.ramp_note = r.String("ramp_note");
  r.ExpectAllKeysUsed();
  return d;
}

ReferenceFitDiagnostics ReadReference(const Reader& r) {
  ReferenceFitDiagnostics d;
  d.strategy_steps = r.String("strategy_steps");
  const Reader thermal = r.Child("thermal");
  for (const std::string& ch : thermal.ChannelKeys())
    d.thermal[ch] = ReadThermal(thermal.Child(ch));
  const json& accel = r.Array("accel");
  for (size_t i = 0; i < accel.size(); ++i) {
    const Reader a = r.Element(accel, i, "accel");
    d.accel.push_back({a.String("channel"),
                       a.Number("inverse_scale_g_per_duty"),
                       a.Number("inverse_scale_se_g_per_duty")});
    a.ExpectAllKeysUsed();
  }
  const json& gyro = r.Array("gyro");
  for (size_t i = 0; i < gyro.size(); ++i) {
    const Reader g = r.Element(gyro, i, "gyro");
    d.gyro.push_back({g.String("channel"), g.Int("rates"), g.Number("residual_rms_dps")});
    g.ExpectAllKeysUsed();
  }
  const Reader c = r.Child("cross_axis");
  d.cross_axis = {c.String("source"), c.Number("ca_condition"), c.Number("cg_condition")};
  c.ExpectAllKeysUsed();
  return d;
}

BiasWanderDiagnostics ReadWander(const Reader& r) {
  BiasWanderDiagnostics w;
  w.floor_dph = r.Number("floor_dph");
  w.time_scale = r.Number("time_scale");
  w.source = r.String("source");
  if (r.Has("white_variance_scale")) w.white_variance_scale = r.Number("white_variance_scale");
  if (r.Has("log_likelihood_gain_over_datasheet"))
    w.log_likelihood_gain_over_datasheet = r.Number("log_likelihood_gain_over_datasheet");
  if (r.Has("at_grid_edge")) w.at_grid_edge = r.Flag("at_grid_edge");
  r.ExpectAllKeysUsed();
  return w;
}

void ReadFormatTerms(const Reader& r, JointChannelDiagnostics* c) {
  if (r.Has("scale_temperature_levels"))
    c->scale_temperature_levels = r.Int("scale_temperature_levels");
  if (r.Has("scale_min_order")) c->scale_min_order = r.Int("scale_min_order");
  if (r.Has("scale_held_out_normalised_rms_by_order")) {
    const std::string key = "scale_held_out_normalised_rms_by_order";
    const json& scores = r.Array(key);
    for (size_t i = 0; i < scores.size(); ++i) {
      const std::string where = r.PathOf(key) + "[" + std::to_string(i) + "]";
      if (scores[i].is_null()) {
        c->scale_held_out_normalised_rms_by_order.push_back(std::nullopt);
      } else {
        c->scale_held_out_normalised_rms_by_order.push_back(r.NumberAt(scores[i], where));
      }
    }
  }
  if (r.Has("scale_order")) c->scale_order = r.Int("scale_order");
  if (r.Has("scale_tempco_ppm_per_c"))
    c->scale_tempco_ppm_per_c = r.Number("scale_tempco_ppm_per_c");
  if (r.Has("scale_tempco_se_ppm_per_c"))
    c->scale_tempco_se_ppm_per_c = r.Number("scale_tempco_se_ppm_per_c");
  if (r.Has("scale_tempco_note")) c->scale_tempco_note = r.String("scale_tempco_note");
}

JointChannelDiagnostics ReadJointChannel(const Reader& r) {
  JointChannelDiagnostics c;
  c.model_error_rms = r.Number("model_error_rms");
  c.thermal_order = r.Int("thermal_order");
  c.observations = r.Int("observations");
  c.residual_rms = r.Number("residual_rms");
  c.sigma_ratio_to_datasheet = r.Number("sigma_ratio_to_datasheet");
  if (r.Has("held_out_normalised_rms_by_order"))
    c.held_out_normalised_rms_by_order = r.Numbers("held_out_normalised_rms_by_order");
  if (r.Has("bias_wander")) c.bias_wander = ReadWander(r.Child("bias_wander"));
  ReadFormatTerms(r, &c);
  r.ExpectAllKeysUsed();
  return c;
}

JointFitDiagnostics ReadJoint(const Reader& r) {
  JointFitDiagnostics d;
  const Reader channels = r.Child("channels");
  for (const std::string& ch : channels.ChannelKeys())
    d.channels[ch] = ReadJointChannel(channels.Child(ch));
  d.observations = r.Integer("observations");
  d.crb_parameters = r.Strings("crb_parameters");
  const json& rows = r.Array("crb_covariance");
  for (size_t i = 0; i < rows.size(); ++i) {
    d.crb_covariance.push_back(
        r.Numbers(rows[i], r.PathOf("crb_covariance") + "[" + std::to_string(i) + "]"));
  }
  d.firmware_cannot_hold = r.String("firmware_cannot_hold");
  return d;
}

}  // namespace

ImuFitDiagnostics ImuFitDiagnostics::FromJson(const json& j,
                                              const std::string& source,
                                              const std::string& path) {
  const Reader r(j, source, path);
  ImuFitDiagnostics d;
  if (r.Has("strategy_steps")) d.reference = ReadReference(r);
  if (r.Has("channels")) d.joint = ReadJoint(r);
  if (r.Has("excluded_rows")) d.excluded_rows = r.Integer("excluded_rows");
  if (r.Has("exclusions")) d.exclusions = r.Strings("exclusions");
  if (r.Has("rejected_interval_rows"))
    d.rejected_interval_rows = r.Integer("rejected_interval_rows");
  if (r.Has("local_gravity_mps2")) d.local_gravity_mps2 = r.Number("local_gravity_mps2");
  r.ExpectAllKeysUsed();
  return d;
}

}  // namespace adahrs::calib
