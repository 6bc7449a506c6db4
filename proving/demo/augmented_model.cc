#include "proving/demo/augmented_model.h"

#include <cmath>
#include <map>

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/imu_layout.h"
#include "common/param_reader.h"
#include "sensor_sim/ads_unit.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::proving {
namespace {

using common::ParamError;
using common::ParamReader;

int ImuChannel(const std::string& name) {
  for (int ch = 0; ch < diagnosis::kImuChannels; ++ch) {
    if (name == common::kImuChannelNames[ch]) return ch;
  }
  return -1;
}

double Component(const diagnosis::Finding& f, const std::string& name) {
  for (const diagnosis::FindingComponent& c : f.components) {
    if (c.name == name) return c.magnitude;
  }
  throw ParamError(
      fmt::format("finding {} on {} has no component '{}'", f.effect, f.channel, name));
}

struct Weighted {
  double sum = 0.0, weight = 0.0;
};

void ApplyImu(const diagnosis::UnitDiagnosis& d,
              sensor_sim::ImuUnitParams* p,
              AugmentedModel* out) {
  std::map<int, Weighted> lag;  // accelerometer chip -> delay over its thermometer die
  for (const diagnosis::Finding& f : d.findings) {
    const int ch = ImuChannel(f.channel);
    const std::string what = f.channel + " " + f.effect;
    if (f.effect == "gyro_g_sensitivity" && ch >= 6) {
      const Eigen::Vector3d b(Component(f, "x"), Component(f, "y"), Component(f, "z"));
      const Eigen::Vector3d g = p->geometry.R_GB(ch - 6) * b;
      auto& gyro = p->gyros[static_cast<size_t>(ch - 6)];
      for (int k = 0; k < 3; ++k) gyro.g_sensitivity_dps_per_g[static_cast<size_t>(k)] = g[k];
      gyro.effects.g_sensitivity = true;
      out->applied.push_back(
          fmt::format("gyros[{}].g_sensitivity_dps_per_g = [{:.4g}, {:.4g}, {:.4g}] ({})",
                      ch - 6,
                      g[0],
                      g[1],
                      g[2],
                      what));
    } else if (f.effect == "scale_factor_tempco" && ch >= 0) {
      const double tc1 = Component(f, "tc1"), tc2 = Component(f, "tc2");
      std::string key;
      if (ch >= 6) {
        auto& gyro = p->gyros[static_cast<size_t>(ch - 6)];
        gyro.sensitivity_tc1_ppm_per_c = tc1;
        gyro.sensitivity_tc2_ppm_per_c2 = tc2;
        gyro.effects.sensitivity_tempco = true;
        key = fmt::format("gyros[{}]", ch - 6);
      } else {
        auto& chip = p->accel_chips[static_cast<size_t>(ch / 2)];
        auto& axis = ch % 2 == 0 ? chip.x : chip.y;
        axis.sensitivity_tc1_ppm_per_c = tc1;
        axis.sensitivity_tc2_ppm_per_c2 = tc2;
        axis.sensitivity_tc3_ppm_per_c3 = 0.0;
        chip.effects.sensitivity_tempco = true;
        key = fmt::format("accel_chips[{}].{}", ch / 2, ch % 2 == 0 ? "x" : "y");
      }
      out->applied.push_back(
          fmt::format("{}.sensitivity_tc1, tc2 = {:.4g} ppm/degC, {:.4g} ppm/degC^2 ({})",
                      key,
                      tc1,
                      tc2,
                      what));
    } else if (f.effect == "die_thermal_lag" && ch >= 0 && ch < 6) {
      const double se = std::max(f.components[0].standard_error, 1e-9);
      lag[ch / 2].sum += Component(f, "delay") / (se * se);
      lag[ch / 2].weight += 1.0 / (se * se);
    } else if (f.effect == "table_rate_ripple") {
      out->not_applied.push_back(
          what + ": the rate table's, not the unit's (rig.json rate_table.rate_ripple_ratio)");
    } else {
      out->not_applied.push_back(what + ": the unit schema has no parameter of this form");
    }
  }
  for (const auto& [chip, w] : lag) {
    const auto& thermometer = p->gyro_thermal[static_cast<size_t>(
        common::kImuChannels[static_cast<size_t>(2 * chip)].thermometer)];
    const double tau = (thermometer.effects.lag ? thermometer.tau_s : 0.0) + w.sum / w.weight;
    if (!(tau > 0.0)) {
      out->not_applied.push_back(fmt::format(
          "accelerometer chip {} die_thermal_lag: the die would lead the air ({:.3g} s)",
          chip,
          tau));
      continue;
    }
    auto& die = p->accel_thermal[static_cast<size_t>(chip)];
    die.tau_s = tau;
    die.effects.lag = true;
    out->applied.push_back(
        fmt::format("accel_thermal[{}].tau_s = {:.4g} s (die_thermal_lag)", chip, tau));
  }
}

void ApplyAds(const diagnosis::UnitDiagnosis& d,
              sensor_sim::AdsUnitParams* p,
              AugmentedModel* out) {
  for (const diagnosis::Finding& f : d.findings) {
    const std::string what = f.channel + " " + f.effect;
    const bool pitot = f.channel == "pt";
    if ((f.channel != "ps" && !pitot) ||
        (f.effect != "pressure_hysteresis" && f.effect != "thermal_hysteresis")) {
      out->not_applied.push_back(what + ": the unit schema has no parameter of this form");
      continue;
    }
    auto& b = pitot ? p->pitot_bridge : p->static_bridge;
    const std::string key = pitot ? "pitot_bridge" : "static_bridge";
    const double h_pct = 2.0 * Component(f, "half_loop") / b.full_scale_pa * 100.0;
    b.hysteresis_law = sensor_sim::HysteresisLaw::kTravelPreisach;  // the diagnoser's law
    if (f.effect == "pressure_hysteresis") {
      b.pressure_hysteresis_pct_fso = h_pct;
      b.pressure_hysteresis_span_pct_fs = Component(f, "span") / b.full_scale_pa * 100.0;
      b.effects.pressure_hysteresis = true;
      out->applied.push_back(
          fmt::format("{}.pressure_hysteresis_pct_fso = {:.4g}, span {:.4g} % FS ({})",
                      key,
                      h_pct,
                      b.pressure_hysteresis_span_pct_fs,
                      what));
    } else {
      b.thermal_hysteresis_pct_fso = h_pct;
      b.thermal_hysteresis_span_c = Component(f, "span");
      b.effects.thermal_hysteresis = true;
      out->applied.push_back(
          fmt::format("{}.thermal_hysteresis_pct_fso = {:.4g}, span {:.4g} degC ({})",
                      key,
                      h_pct,
                      b.thermal_hysteresis_span_c,
                      what));
    }
  }
}

}  // namespace

AugmentedModel AugmentUnitModel(const diagnosis::UnitDiagnosis& diagnosis,
                                const std::filesystem::path& base_file) {
  const std::string path = base_file.string();
  const nlohmann::json base = ParamReader::LoadFile(path);
  const ParamReader top(base, path);
  const std::string kind = top.String("kind");
  if (kind != "imu" && kind != "ads")
    throw ParamError(path + ": $.kind: '" + kind + "' is not imu or ads");
  AugmentedModel out;
  out.model = base;
  const ParamReader params = top.Child("params");
  if (kind == "imu") {
    sensor_sim::ImuUnitParams p = sensor_sim::ImuUnitParams::FromJson(params);
    ApplyImu(diagnosis, &p, &out);
    out.model["params"] = p.ToJson();
  } else {
    sensor_sim::AdsUnitParams p = sensor_sim::AdsUnitParams::FromJson(params);
    ApplyAds(diagnosis, &p, &out);
    out.model["params"] = p.ToJson();
  }
  const std::string serial = out.model["params"]["serial"].get<std::string>();
  if (serial != diagnosis.serial) {
    throw ParamError(fmt::format("{}: $.params.serial: '{}' is not the diagnosed unit '{}'",
                                 path,
                                 serial,
                                 diagnosis.serial));
  }
  // The range checks of the schema: a fitted value no part could have is refused here.
  const std::string written = path + " with the findings applied";
  if (kind == "imu") {
    sensor_sim::ImuUnitParams::FromJson(ParamReader(out.model["params"], written, "$.params"));
  } else {
    sensor_sim::AdsUnitParams::FromJson(ParamReader(out.model["params"], written, "$.params"));
  }
  return out;
}

AugmentedModel WriteAugmentedModel(const diagnosis::DiagnosisRun& run,
                                   const std::filesystem::path& base_file,
                                   const std::filesystem::path& out_dir) {
  const nlohmann::json base = ParamReader::LoadFile(base_file.string());
  const ParamReader top(base, base_file.string());
  const std::string serial = top.Child("params").String("serial");
  for (const diagnosis::UnitDiagnosis& u : run.units) {
    if (u.serial != serial) continue;
    AugmentedModel m = AugmentUnitModel(u, base_file);
    std::filesystem::create_directories(out_dir);
    common::WriteFileAtomically(out_dir / "model.json", m.model.dump(2) + "\n");
    return m;
  }
  throw ParamError(
      fmt::format("{}: $.params.serial: '{}' is not a unit of the diagnosed recordings",
                  base_file.string(),
                  serial));
}

}  // namespace adahrs::proving
