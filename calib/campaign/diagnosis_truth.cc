#include "calib/campaign/diagnosis_truth.h"

#include <cmath>

#include <fmt/format.h>

#include "sensor_sim/imu_unit.h"
#include "sensor_sim/param_reader.h"

namespace adahrs::calib {
namespace {

sensor_sim::ImuUnitParams ReadTruth(const std::filesystem::path& truth_dir, const std::string& serial) {
  const std::string path = (truth_dir / (serial + ".json")).string();
  const nlohmann::json truth = sensor_sim::ParamReader::LoadFile(path);
  if (!truth.is_object() || !truth.contains("params")) {
    throw sensor_sim::ParamError(path + ": $.params: missing (not a rig truth file)");
  }
  return sensor_sim::ImuUnitParams::FromJson(sensor_sim::ParamReader(truth["params"], path, "$.params"));
}

const sensor_sim::Adxl210eAxisParams& Axis(const sensor_sim::ImuUnitParams& p, int ch) {
  return ch % 2 == 0 ? p.accel_chips[ch / 2].x : p.accel_chips[ch / 2].y;
}

// The truth's value of `effect` on `ch` per finding component, empty when the truth does not
// have the effect on.
std::vector<double> TruthOf(const sensor_sim::ImuUnitParams& p, const std::string& effect, int ch) {
  if (effect == "die_thermal_lag" && ch < 6) {
    const auto& a = p.accel_thermal[ch / 2];
    const auto& g = p.gyro_thermal[kChannelThermometer[ch]];
    if (!a.effects.lag && !g.effects.lag) return {};
    return {(a.effects.lag ? a.tau_s : 0.0) - (g.effects.lag ? g.tau_s : 0.0)};
  }
  if (effect == "gyro_g_sensitivity" && ch >= 6) {
    const auto& g = p.gyros[ch - 6];
    if (!g.effects.g_sensitivity) return {};
    const Eigen::Vector3d b = p.geometry.R_GB(ch - 6).transpose() * Eigen::Vector3d(g.g_sensitivity_dps_per_g.data());
    return {b[0], b[1], b[2]};
  }
  if (effect == "scale_factor_tempco") {
    if (ch < 6) {
      if (!p.accel_chips[ch / 2].effects.sensitivity_tempco) return {};
      return {Axis(p, ch).sensitivity_tc1_ppm_per_c, Axis(p, ch).sensitivity_tc2_ppm_per_c2};
    }
    const auto& g = p.gyros[ch - 6];
    if (!g.effects.sensitivity_tempco) return {};
    return {g.sensitivity_tc1_ppm_per_c, g.sensitivity_tc2_ppm_per_c2};
  }
  return {};
}

std::string Values(const std::vector<double>& v) {
  std::string s;
  for (double x : v) s += fmt::format("{}{:.3g}", s.empty() ? "" : ", ", x);
  return s;
}

}  // namespace

std::vector<DiagnosisTruthLine> CompareDiagnosisWithTruth(const std::vector<UnitDiagnosis>& units,
                                                          const std::filesystem::path& truth_dir) {
  std::vector<DiagnosisTruthLine> out;
  for (const UnitDiagnosis& u : units) {
    const sensor_sim::ImuUnitParams truth = ReadTruth(truth_dir, u.serial);
    for (int ch = 0; ch < kImuChannels; ++ch) {
      for (const char* effect : {"die_thermal_lag", "gyro_g_sensitivity", "scale_factor_tempco"}) {
        const std::vector<double> t = TruthOf(truth, effect, ch);
        const Finding* found = nullptr;
        for (const Finding& f : u.findings) {
          if (f.effect == effect && f.channel == kImuChannelNames[ch]) found = &f;
        }
        if (found == nullptr && t.empty()) continue;
        DiagnosisTruthLine line{u.serial, effect, kImuChannelNames[ch], found != nullptr, ""};
        if (found != nullptr) {
          std::string comps;
          for (const FindingComponent& c : found->components) {
            comps += fmt::format("{}{:.3g} ± {:.2g}", comps.empty() ? "" : ", ", c.magnitude, c.standard_error);
          }
          line.text = fmt::format("found {} {}; truth {}", comps, found->components[0].unit,
                                  t.empty() ? "does not have it" : Values(t));
        } else {
          std::string why = "no limit";
          for (const DetectionLimit& l : u.detection_limits) {
            if (l.effect != effect || l.channel != kImuChannelNames[ch]) continue;
            why = l.limits.empty() ? l.note
                                   : fmt::format("below this recording's detection limit ({} {})",
                                                 Values([&] {
                                                   std::vector<double> v;
                                                   for (const FindingComponent& c : l.limits) v.push_back(c.magnitude);
                                                   return v;
                                                 }()),
                                                 l.limits[0].unit);
          }
          line.text = fmt::format("not found (truth {}): {}", Values(t), why);
        }
        out.push_back(std::move(line));
      }
    }
  }
  return out;
}

}  // namespace adahrs::calib
