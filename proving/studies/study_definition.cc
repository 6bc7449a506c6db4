#include "proving/studies/study_definition.h"

#include "calib/ads_calibration/tolerance_ads_strategy.h"
#include "calib/sequence/execution_plan.h"
#include "calib/sequence/sequence_json.h"
#include "calib/sequence/validation.h"
#include "common/param_reader.h"
#include "common/unit_kind.h"

namespace adahrs::proving {
namespace {

using common::ParamError;
using common::ParamReader;

bool IsFileName(const std::string& spec) { return spec.ends_with(".json"); }

std::filesystem::path Resolve(const std::string& spec, const std::filesystem::path& relative_to) {
  const std::filesystem::path p(spec);
  return p.is_absolute() ? p : relative_to / p;
}

StudyPopulation ReadPopulationFile(const std::filesystem::path& file) {
  const nlohmann::json j = ParamReader::LoadFile(file.string());
  const ParamReader r(j, file.string());
  if (r.String("format") != "adahrs-population")
    r.Fail("$.format", "expected \"adahrs-population\"");
  r.Integer("format_version", 1, 1);
  StudyPopulation p;
  const std::string profile = r.String("profile");
  if (profile != "truth" && profile != "nominal") {
    r.Fail("$.profile", "expected \"truth\" or \"nominal\", got \"" + profile + "\"");
  }
  p.profile = sensor_sim::ModelProfileFromString(profile);
  if (r.Has("variant")) {
    const std::string variant = r.String("variant");
    try {
      p.variant = sensor_sim::TruthVariantFromString(variant);
    } catch (const std::exception& e) {
      r.Fail("$.variant", e.what());
    }
  }
  r.ExpectAllKeysUsed();
  return p;
}

// "reference", "improved" (hysteresis_compensated, the strategy the demo downloads) or another name
// FitAdsStrategy knows.
std::string AdsStrategyName(const std::string& label, const ParamReader& r) {
  if (label == "improved") return calib::kHysteresisAdsStrategyName;
  for (const char* known : {calib::kReferenceAdsStrategyName,
                            calib::kToleranceAdsStrategyName,
                            calib::kPressureAdsStrategyName,
                            calib::kHysteresisAdsStrategyName}) {
    if (label == known) return label;
  }
  r.Fail("$.strategy",
         "unknown ADS strategy \"" + label +
             "\" (expected \"reference\", \"improved\", \"tolerance_minimax\", "
             "\"pressure_minimax\" or \"hysteresis_compensated\")");
  return {};
}

}  // namespace

std::string StudyPopulation::Label() const {
  const std::string base = sensor_sim::ToString(profile);
  return variant == sensor_sim::TruthVariant::kStandard
             ? base
             : base + "/" + sensor_sim::ToString(variant);
}

StudyPopulation ParsePopulation(const std::string& spec,
                                const std::filesystem::path& relative_to,
                                const std::string& source,
                                const std::string& json_path) {
  if (spec == "truth") return {sensor_sim::ModelProfile::kTruth};
  if (spec == "nominal") return {sensor_sim::ModelProfile::kNominal};
  if (!IsFileName(spec)) {
    throw ParamError(source + ": " + json_path +
                     ": expected \"truth\", \"nominal\" or a population "
                     "file (.json), got \"" +
                     spec + "\"");
  }
  return ReadPopulationFile(Resolve(spec, relative_to));
}

StudyDefinition LoadStudyDefinition(const std::filesystem::path& file,
                                    const std::filesystem::path& shipped_sequence_dir) {
  const nlohmann::json j = ParamReader::LoadFile(file.string());
  const ParamReader r(j, file.string());
  const std::filesystem::path dir = file.parent_path();
  if (r.String("format") != "adahrs-study") r.Fail("$.format", "expected \"adahrs-study\"");
  r.Integer("format_version", 1, 1);
  const std::string kind = r.String("unit_kind");
  const std::optional<calib::UnitKind> parsed = common::ParseUnitKind(kind);
  if (!parsed) r.Fail("$.unit_kind", "expected \"imu\" or \"ads\", got \"" + kind + "\"");

  StudyDefinition d;
  d.unit_kind = *parsed;
  d.name = file.stem().string();
  d.file = file.string();
  const std::string sequence = r.String("sequence");
  d.sequence_file = IsFileName(sequence) ? Resolve(sequence, dir).string()
                                         : (shipped_sequence_dir / (sequence + ".json")).string();
  if (!IsFileName(sequence) && !std::filesystem::exists(d.sequence_file)) {
    r.Fail("$.sequence",
           "no shipped sequence \"" + sequence + "\" in " + shipped_sequence_dir.string());
  }
  const calib::SequenceLimits limits;
  const std::vector<calib::SequenceProblem> problems =
      calib::CheckSequenceFile(d.sequence_file, limits);
  if (!problems.empty()) {
    std::string list;
    for (const calib::SequenceProblem& p : problems) list += "\n  " + p.Format(d.sequence_file);
    r.Fail("$.sequence", "the validator refuses " + d.sequence_file + ":" + list);
  }
  d.sequence = calib::LoadValidSequence(d.sequence_file, limits);
  if (d.sequence.unit_kind != d.unit_kind) {
    r.Fail("$.sequence",
           d.sequence_file + " is not an " + (kind == "ads" ? "ADS" : "IMU") + " sequence");
  }
  d.rig_time_s = calib::ExpandSequence(d.sequence, limits).duration_estimate_s;

  d.strategy_label = r.String("strategy");
  if (d.unit_kind == calib::UnitKind::kAds) {
    d.ads_strategy = AdsStrategyName(d.strategy_label, r);
  } else if (d.strategy_label == "reference") {
    d.strategy = calib::ImuStrategy::Reference();
  } else if (d.strategy_label == "improved") {
    d.strategy = calib::ImuStrategy::JointFormat2();
  } else if (IsFileName(d.strategy_label)) {
    d.strategy = calib::ImuStrategy::Load(Resolve(d.strategy_label, dir));
  } else {
    r.Fail("$.strategy",
           "unknown strategy \"" + d.strategy_label +
               "\" (expected \"reference\", \"improved\" or an adahrs-imu-strategy file .json)");
  }
  if (r.Has("population")) {
    d.population = ParsePopulation(r.String("population"), dir, file.string(), "$.population");
  }
  r.ExpectAllKeysUsed();
  return d;
}

}  // namespace adahrs::proving
