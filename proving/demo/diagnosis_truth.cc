#include "proving/demo/diagnosis_truth.h"

#include <cmath>
#include <map>

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/imu_layout.h"
#include "common/param_reader.h"
#include "diagnosis/replay_check_report.h"
#include "hil/recording/recording_reader.h"
#include "proving/demo/augmented_model.h"
#include "proving/evaluation/truth_file.h"
#include "sensor_sim/ads_unit.h"
#include "sensor_sim/imu_unit.h"

namespace adahrs::proving {
namespace {

nlohmann::json TruthJson(const std::filesystem::path& truth_dir, const std::string& serial) {
  return proving::ReadTruthFile(truth_dir / (serial + ".json")).file;
}

sensor_sim::ImuUnitParams ReadTruth(const std::filesystem::path& truth_dir,
                                    const std::string& serial) {
  return ImuTruth(proving::ReadTruthFile(truth_dir / (serial + ".json")), serial);
}

sensor_sim::AdsUnitParams ReadAdsTruth(const std::filesystem::path& truth_dir,
                                       const std::string& serial) {
  return AdsTruth(proving::ReadTruthFile(truth_dir / (serial + ".json")), serial);
}

// The truth's half loop (Pa) and span (Pa or degC) of a bridge's hysteresis, empty when it is off.
std::vector<double> AdsTruthOf(const sensor_sim::AdsUnitParams& p,
                               const std::string& effect,
                               const std::string& ch) {
  const sensor_sim::PressureBridgeParams& b = ch == "ps" ? p.static_bridge : p.pitot_bridge;
  if (effect == "pressure_hysteresis" && b.effects.pressure_hysteresis) {
    return {b.pressure_hysteresis_pct_fso / 200.0 * b.full_scale_pa,
            b.pressure_hysteresis_span_pct_fs / 100.0 * b.full_scale_pa};
  }
  if (effect == "thermal_hysteresis" && b.effects.thermal_hysteresis) {
    return {b.thermal_hysteresis_pct_fso / 200.0 * b.full_scale_pa, b.thermal_hysteresis_span_c};
  }
  return {};
}

const sensor_sim::Adxl210eAxisParams& Axis(const sensor_sim::ImuUnitParams& p, int ch) {
  return ch % 2 == 0 ? p.accel_chips[ch / 2].x : p.accel_chips[ch / 2].y;
}

// The truth's value of `effect` on `ch` per finding component, empty when the truth does not
// have the effect on.
std::vector<double> TruthOf(const sensor_sim::ImuUnitParams& p, const std::string& effect, int ch) {
  if (effect == "die_thermal_lag" && ch < 6) {
    const auto& a = p.accel_thermal[ch / 2];
    const auto& g = p.gyro_thermal[common::kImuChannels[ch].thermometer];
    if (!a.effects.lag && !g.effects.lag) return {};
    return {(a.effects.lag ? a.tau_s : 0.0) - (g.effects.lag ? g.tau_s : 0.0)};
  }
  if (effect == "gyro_g_sensitivity" && ch >= 6) {
    const auto& g = p.gyros[ch - 6];
    if (!g.effects.g_sensitivity) return {};
    const Eigen::Vector3d b =
        p.geometry.R_GB(ch - 6).transpose() * Eigen::Vector3d(g.g_sensitivity_dps_per_g.data());
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

// The line of one (unit, channel, effect): the finding beside the truth, or why it was not found.
DiagnosisTruthLine TruthLine(const diagnosis::UnitDiagnosis& u,
                             const std::string& effect,
                             const std::string& channel,
                             const std::vector<double>& t,
                             const diagnosis::Finding* found) {
  DiagnosisTruthLine line{u.serial, effect, channel, found != nullptr, ""};
  if (found != nullptr) {
    std::string comps;
    for (const diagnosis::FindingComponent& c : found->components) {
      comps += fmt::format(
          "{}{:.3g} ± {:.2g}", comps.empty() ? "" : ", ", c.magnitude, c.standard_error);
    }
    line.text = fmt::format("found {} {}; truth {}",
                            comps,
                            found->components[0].unit,
                            t.empty() ? "does not have it" : Values(t));
    return line;
  }
  std::string why = "no limit";
  for (const diagnosis::DetectionLimit& l : u.detection_limits) {
    if (l.effect != effect || l.channel != channel) continue;
    std::vector<double> limits;
    for (const diagnosis::FindingComponent& c : l.limits) limits.push_back(c.magnitude);
    why = l.limits.empty() ? l.note
                           : fmt::format("below this recording's detection limit ({} {})",
                                         Values(limits),
                                         l.limits[0].unit);
  }
  line.text = fmt::format("not found (truth {}): {}", Values(t), why);
  return line;
}

const diagnosis::Finding* FindingOf(const diagnosis::UnitDiagnosis& u,
                                    const std::string& effect,
                                    const std::string& channel) {
  for (const diagnosis::Finding& f : u.findings) {
    if (f.effect == effect && f.channel == channel) return &f;
  }
  return nullptr;
}

}  // namespace

std::vector<DiagnosisTruthLine> CompareDiagnosisWithTruth(
    const std::vector<diagnosis::UnitDiagnosis>& units, const std::filesystem::path& truth_dir) {
  std::vector<DiagnosisTruthLine> out;
  for (const diagnosis::UnitDiagnosis& u : units) {
    const bool ads = proving::ReadTruthFile(truth_dir / (u.serial + ".json")).kind == "ads";
    if (ads) {
      const sensor_sim::AdsUnitParams truth = ReadAdsTruth(truth_dir, u.serial);
      for (const char* ch : {"ps", "pt"}) {
        for (const char* effect : {"pressure_hysteresis", "thermal_hysteresis"}) {
          const std::vector<double> t = AdsTruthOf(truth, effect, ch);
          const diagnosis::Finding* found = FindingOf(u, effect, ch);
          if (found != nullptr || !t.empty()) out.push_back(TruthLine(u, effect, ch, t, found));
        }
      }
      continue;
    }
    const sensor_sim::ImuUnitParams truth = ReadTruth(truth_dir, u.serial);
    for (int ch = 0; ch < diagnosis::kImuChannels; ++ch) {
      for (const char* effect : {"die_thermal_lag", "gyro_g_sensitivity", "scale_factor_tempco"}) {
        const std::vector<double> t = TruthOf(truth, effect, ch);
        const diagnosis::Finding* found = FindingOf(u, effect, common::kImuChannelNames[ch]);
        if (found != nullptr || !t.empty())
          out.push_back(TruthLine(u, effect, common::kImuChannelNames[ch], t, found));
      }
    }
  }
  return out;
}

nlohmann::json BaseModelFromTruth(const std::filesystem::path& truth_dir,
                                  const std::string& serial) {
  nlohmann::json file = TruthJson(truth_dir, serial);
  if (file.value("kind", "") == "ads") {
    sensor_sim::AdsUnitParams p = ReadAdsTruth(truth_dir, serial);
    for (sensor_sim::PressureBridgeParams* b : {&p.static_bridge, &p.pitot_bridge}) {
      b->effects.pressure_hysteresis = false;
      b->effects.thermal_hysteresis = false;
    }
    file["params"] = p.ToJson();
  } else {
    sensor_sim::ImuUnitParams p = ReadTruth(truth_dir, serial);
    for (auto& g : p.gyros) {
      g.effects.g_sensitivity = false;
      g.effects.sensitivity_tempco = false;
    }
    for (size_t c = 0; c < p.accel_chips.size(); ++c) {
      p.accel_chips[c].effects.sensitivity_tempco = false;
      const auto& thermometer =
          p.gyro_thermal[static_cast<size_t>(common::kImuChannels[2 * c].thermometer)];
      p.accel_thermal[c].tau_s = thermometer.tau_s;
      p.accel_thermal[c].effects.lag = thermometer.effects.lag;
    }
    file["params"] = p.ToJson();
  }
  file["model_profile"] = "truth without the diagnosis vocabulary's effects";
  return file;
}

std::vector<diagnosis::ReplayComparison> CheckDiagnosisByReplay(
    const diagnosis::DiagnosisRun& diagnosed,
    const std::filesystem::path& truth_dir,
    const std::filesystem::path& diagnosis_dir,
    const std::vector<std::filesystem::path>& check_runs,
    const diagnosis::ReplayFunction& replay) {
  std::map<std::string, std::pair<std::filesystem::path, std::filesystem::path>>
      files;  // base, model
  for (const diagnosis::UnitDiagnosis& u : diagnosed.units) {
    const std::filesystem::path dir = diagnosis_dir / "models" / u.serial;
    std::filesystem::create_directories(dir);
    common::WriteFileAtomically(dir / "base.json",
                                BaseModelFromTruth(truth_dir, u.serial).dump(2) + "\n");
    WriteAugmentedModel(diagnosed, dir / "base.json", dir);
    files[u.serial] = {dir / "base.json", dir / "model.json"};
  }
  std::vector<diagnosis::ReplayComparison> out;
  for (const std::filesystem::path& run : check_runs) {
    std::vector<std::filesystem::path> bases, models;
    for (const hil::RecordingUnit& unit : hil::ReadRecordingMeta(run).meta.units) {
      const auto f = files.find(unit.serial);
      if (f == files.end()) continue;
      bases.push_back(f->second.first);
      models.push_back(f->second.second);
    }
    if (bases.empty()) continue;
    const std::filesystem::path work = diagnosis_dir / "replay" / run.filename();
    out.push_back(diagnosis::CheckByReplay(run, bases, models, work, true, replay));
    std::filesystem::remove_all(work);
  }
  std::filesystem::remove_all(diagnosis_dir / "replay");
  diagnosis::WriteReplayCheck(out, diagnosis_dir);
  return out;
}

}  // namespace adahrs::proving
