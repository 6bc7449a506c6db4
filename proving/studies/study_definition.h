// A study file: which sequence a strategy's units run, which fit strategy turns the recording into
// constants ("reference", "improved" or a strategy file; for ADS also a FitAdsStrategy name), and
// optionally the unit population ("truth", "nominal" or an adahrs-population file). The sequence
// (a shipped name or a file relative to the study file) must pass the validator
// (calib/sequence/validation.h) and be for the study file's unit kind; its rig time is the
// execution plan's duration estimate on real instruments (ExpandSequence). Errors throw
// common::ParamError naming the file and the JSON path.
// Keys, values and refusals: docs/studies.md ("Study files").
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "calib/imu_calibration/imu_strategy.h"
#include "calib/sequence/sequence.h"
#include "sensor_sim/model_profile.h"

namespace adahrs::proving {

struct StudyPopulation {
  sensor_sim::ModelProfile profile = sensor_sim::ModelProfile::kTruth;
  sensor_sim::TruthVariant variant = sensor_sim::TruthVariant::kStandard;

  std::string Label() const;  ///< "truth", "nominal", "truth/slow_bias_wander"
  bool operator==(const StudyPopulation&) const = default;
};

/// "truth", "nominal" or a population file; `source` and `json_path` name where the spec came
/// from in errors (a study file's $.population, or the command line).
StudyPopulation ParsePopulation(const std::string& spec,
                                const std::filesystem::path& relative_to,
                                const std::string& source,
                                const std::string& json_path);

struct StudyDefinition {
  std::string name;           ///< the study file's stem: the strategy's name in results
  std::string file;           ///< the study file
  std::string sequence_file;  ///< the sequence it runs
  calib::Sequence sequence;
  double rig_time_s = 0.0;     ///< the execution plan's duration estimate
  std::string strategy_label;  ///< "reference", "improved" or the strategy file
  calib::ImuStrategy strategy;
  calib::UnitKind unit_kind = calib::UnitKind::kImu;
  std::string ads_strategy;  ///< ADS studies: the FitAdsStrategy name
  std::optional<StudyPopulation> population;
};

/// Reads and checks a study file; shipped sequence names resolve in `shipped_sequence_dir`.
StudyDefinition LoadStudyDefinition(const std::filesystem::path& file,
                                    const std::filesystem::path& shipped_sequence_dir);

}  // namespace adahrs::proving
