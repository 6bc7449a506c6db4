#include "calib/imu_calibration/imu_strategy.h"

#include <algorithm>

#include "calib/imu_calibration/imu_joint_fit.h"
#include "calib/imu_calibration/imu_observations.h"
#include "calib/imu_calibration/imu_reference_fit.h"
#include "calib/imu_calibration/imu_run_data.h"
#include "common/param_reader.h"

namespace adahrs::calib {

ImuStrategy ImuStrategy::Reference() {
  ImuStrategy s;
  s.name = "reference";
  return s;
}

ImuStrategy ImuStrategy::JointFormat2() { return ImuStrategy{}; }

ImuStrategy ImuStrategy::JointFormat3() {
  ImuStrategy s;
  s.format3 = true;
  return s;
}

ImuStrategy ImuStrategy::Load(const std::filesystem::path& path) {
  const nlohmann::json j = common::ParamReader::LoadFile(path.string());
  const common::ParamReader r(j, path.string());
  if (r.String("format") != "adahrs-imu-strategy")
    r.Fail("$.format", "expected \"adahrs-imu-strategy\"");
  if (r.Integer("format_version", 1, 1) != 1) r.Fail("$.format_version", "expected 1");
  ImuStrategy s;
  if (r.Has("program")) {
    s.external = ReadExternalProgram(r, j, path);
    s.name = s.external->name;
    r.ExpectAllKeysUsed();
    return s;
  }
  s.name = r.String("strategy");
  if (s.name != "reference" && s.name != "joint") {
    r.Fail("$.strategy",
           "expected \"reference\" or \"joint\" (or a \"program\" to run), got \"" + s.name + "\"");
  }
  if (r.Has("thermal_order")) {
    if (s.name != "joint")
      r.Fail("$.thermal_order", "only the joint strategy chooses a thermal order");
    if (j["thermal_order"].is_string()) {
      if (r.String("thermal_order") != "auto") {
        r.Fail("$.thermal_order",
               "expected \"auto\" or an order 0..." + std::to_string(kMaxThermalOrder));
      }
    } else {
      s.thermal_order = static_cast<int>(r.Integer("thermal_order", 0, kMaxThermalOrder));
    }
  }
  if (r.Has("thermal_band_width_cnt")) {
    s.band_width_cnt = r.Number("thermal_band_width_cnt", 10.0, 2000.0, "counts");
  }
  if (r.Has("gyro_bias_wander")) {
    if (s.name != "joint")
      r.Fail("$.gyro_bias_wander", "only the joint strategy models the gyro bias wander");
    const std::string w = r.String("gyro_bias_wander");
    if (w != "estimated" && w != "datasheet") {
      r.Fail("$.gyro_bias_wander", "expected \"estimated\" or \"datasheet\", got \"" + w + "\"");
    }
    s.estimate_gyro_wander = w == "estimated";
  }
  if (r.Has("firmware_format")) {
    if (s.name != "joint")
      r.Fail("$.firmware_format", "only the joint strategy fits format-3 terms");
    s.format3 = r.Integer("firmware_format", 2, 3) == 3;
  }
  r.ExpectAllKeysUsed();
  return s;
}

ConstantsFile ReadStageBase(const std::string& serial, const ImuStageRequest& staged) {
  const std::filesystem::path path = staged.base_dir / (serial + ".json");
  const std::string stage(ImuStageName(staged.stage));
  if (!std::filesystem::exists(path)) {
    throw ImuInputError("unit " + serial + ": the " + stage + " stage needs " + path.string() +
                        " (the previous stage's constants), which does not exist");
  }
  ConstantsFile base = ReadConstantsFile(path);
  if (base.kind != hil::UnitKind::kImu || base.serial != serial) {
    throw ImuInputError(path.string() + ": constants of " + base.serial + ", not of IMU " + serial);
  }
  const auto held = [&](ImuStage s) {
    return base.stages.empty() ||
           std::find(base.stages.begin(), base.stages.end(), s) != base.stages.end();
  };
  for (ImuStage earlier : StagesThrough(staged.stage)) {
    if (earlier != staged.stage && !held(earlier)) {
      throw ImuInputError(path.string() + ": holds no " + std::string(ImuStageName(earlier)) +
                          " stage, which the " + stage + " stage builds on");
    }
  }
  return base;
}

namespace {

ImuFitResult FitWithStrategy(const ImuUnitData& unit,
                             const ImuRunData& data,
                             const ImuStrategy& strategy,
                             const std::optional<ImuStageRequest>& staged,
                             const std::optional<ConstantsFile>& base) {
  if (strategy.name == "reference") {
    ImuReferenceOptions options;
    options.thermal.band_width_cnt = strategy.band_width_cnt;
    if (staged) options.stage = staged->stage;
    if (base) options.base = ImuStageBase{*base->imu, ImuStandardErrors(*base)};
    return FitImuReference(unit, data.local_gravity_mps2, options);
  }
  ImuJointOptions options;
  options.thermal_order = strategy.thermal_order;
  options.estimate_gyro_wander = strategy.estimate_gyro_wander;
  options.format3 = strategy.format3;
  ImuFitResult fit =
      FitImuJoint(unit.serial,
                  ImuObservations(unit, data.local_gravity_mps2, strategy.band_width_cnt),
                  options);
  fit.diagnostics.excluded_rows = static_cast<int64_t>(unit.exclusions.size());
  fit.diagnostics.rejected_interval_rows = unit.rejected_interval_rows;
  return fit;
}

}  // namespace

ConstantsFile FitImuUnit(const ImuUnitData& unit,
                         const ImuRunData& data,
                         const ImuStrategy& strategy,
                         const std::string& software_version,
                         const std::optional<ImuStageRequest>& staged) {
  if (strategy.external) {
    if (staged) {
      throw ImuInputError("unit " + unit.serial +
                          ": a staged fit is the reference method's; the "
                          "program of strategy \"" +
                          strategy.name + "\" fits every stage at once");
    }
    ExternalExchange exchange;
    return FitImuExternal(unit, data, *strategy.external, software_version, &exchange);
  }
  if (staged && strategy.name != "reference") {
    throw ImuInputError("unit " + unit.serial + ": a staged fit (" +
                        std::string(ImuStageName(staged->stage)) +
                        " stage) is the reference method's; the " + strategy.name +
                        " strategy fits every stage at once");
  }
  std::optional<ConstantsFile> base;
  if (staged && staged->stage != ImuStage::kThermal) base = ReadStageBase(unit.serial, *staged);
  ImuFitResult fit = FitWithStrategy(unit, data, strategy, staged, base);
  fit.diagnostics.local_gravity_mps2 = data.local_gravity_mps2;
  ConstantsFile f;
  f.serial = unit.serial;
  f.kind = hil::UnitKind::kImu;
  f.strategy = strategy.name;
  f.created_utc = UtcNowIso8601();
  f.software_version = software_version;
  f.imu = fit.constants;
  f.standard_errors = ImuStandardErrorsJson(fit.standard_errors);
  if (base) f.provenance = base->provenance;  // the earlier stages' recordings first
  for (const RecordingReference& r : data.recordings) f.provenance.recordings.push_back(r);
  for (const std::string& n : data.sequence_names) f.provenance.sequence_names.push_back(n);
  f.imu_diagnostics = fit.diagnostics;
  if (staged) f.stages = StagesThrough(staged->stage);
  return f;
}

std::vector<ConstantsFile> FitImuRuns(const std::vector<std::filesystem::path>& run_dirs,
                                      const ImuStrategy& strategy,
                                      const std::string& software_version,
                                      const std::optional<ImuStageRequest>& staged) {
  const ImuRunData data = LoadImuRuns(run_dirs);
  std::vector<ConstantsFile> files;
  for (const auto& [serial, unit] : data.units) {
    files.push_back(FitImuUnit(unit, data, strategy, software_version, staged));
  }
  return files;
}

}  // namespace adahrs::calib
