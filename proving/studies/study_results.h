// What a study writes (docs/studies.md "Outputs"): study.json (the settings and strategies, with
// the shard), results.csv (one row per unit and strategy, unit index order; numbers in their
// shortest exact decimal form so a reader gets the same doubles back), and summary.json (per
// strategy: yield per criterion and all, distributions of the worst errors, rig time; with two
// strategies, the paired difference second − first with a bootstrap 95 % interval).
// The summary is a function of study.json and results.csv alone, so merged shards summarise
// exactly as the unsharded study. Errors reading them throw std::runtime_error naming the file
// and, for results.csv, the line and column. For an ADS study (StudyMeta::unit_kind "ads")
// WriteStudyOutputs and ReadResultsCsv hand over to ads_study_results.h. What both kinds share:
// the statistics (study_statistics.h), results.csv's rows (study_csv.h), the report's parts
// (study_report_parts.h) and the summary's JSON entries and files below.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "proving/studies/imu_study.h"
#include "proving/studies/study_statistics.h"

namespace adahrs::proving {

struct StudyStrategyInfo {
  std::string name;  ///< the study file's stem
  std::string file;
  std::string sequence;  ///< the sequence's name
  std::string sequence_file;
  std::string strategy;  ///< "reference", "improved" or the strategy file
  double rig_time_s = 0.0;
  nlohmann::json ToJson() const;
  static StudyStrategyInfo FromJson(const nlohmann::json& j);
  bool operator==(const StudyStrategyInfo&) const = default;
};

struct StudyMeta {
  std::string unit_kind = "imu";  ///< "imu" or "ads"; study.json names it for ADS studies only
  int units = 0;
  uint64_t seed = 0;
  std::string population;
  double g_local_mps2 = 0.0;
  int evaluation_frames = 0;
  std::vector<StudyStrategyInfo> strategies;
  StudyShard shard;
  nlohmann::json ToJson() const;
  static StudyMeta Read(const std::filesystem::path& file);
  /// Equal in everything but the shard.
  bool SameStudy(const StudyMeta& other) const;
};

StudyMeta MakeStudyMeta(const std::vector<StudyDefinition>& strategies,
                        const StudySettings& settings);

struct StrategySummary {
  StudyStrategyInfo info;
  int units = 0;
  int fitted = 0;
  double yield_acceleration = 0.0;  ///< fraction of units passing
  double yield_body_rate = 0.0;
  double yield_body_rate_limit = 0.0;  ///< informative (StrategyOutcome::pass_body_rate_limit)
  double yield_all = 0.0;
  ErrorDistribution worst_accel_mg;
  ErrorDistribution worst_rate_dps;
  nlohmann::json ToJson() const;
};

struct PairedSummary {
  std::string first, second;
  int resamples = 0;
  PairedInterval yield_all;  ///< pass (1/0) second − first, every unit
  PairedInterval yield_acceleration;
  PairedInterval worst_accel_mg;  ///< second − first, units both fitted
  PairedInterval worst_rate_dps;
  nlohmann::json ToJson() const;
};

struct StudySummary {
  int units = 0;
  uint64_t seed = 0;
  std::string population;
  std::vector<StrategySummary> strategies;
  std::optional<PairedSummary> paired;
  nlohmann::json ToJson() const;
};

StudySummary Summarise(const StudyMeta& meta, const std::vector<StudyUnitResult>& results);

void WriteResultsCsv(const std::filesystem::path& file,
                     const StudyMeta& meta,
                     const std::vector<StudyUnitResult>& results);
std::vector<StudyUnitResult> ReadResultsCsv(const std::filesystem::path& file,
                                            const StudyMeta& meta);

/// Writes study.json, results.csv, summary.json and report.html into `dir`.
void WriteStudyOutputs(const std::filesystem::path& dir,
                       const StudyMeta& meta,
                       const std::vector<StudyUnitResult>& results);

// Shared with the ADS study's outputs (ads_study_results.h).
/// summary.json's entry of one strategy: its info, units, fitted, `yield` and the named errors.
nlohmann::json StrategySummaryJson(
    const StudyStrategyInfo& info,
    int units,
    int fitted,
    const nlohmann::json& yield,
    const std::vector<std::pair<std::string, ErrorDistribution>>& errors);
/// summary.json's paired comparison: second − first, the resamples and the named intervals.
nlohmann::json PairedSummaryJson(const std::string& first,
                                 const std::string& second,
                                 int resamples,
                                 const std::vector<std::pair<std::string, PairedInterval>>& rows);
/// Writes study.json, results.csv (`write_csv`), summary.json and report.html into `dir`.
void WriteStudyFiles(const std::filesystem::path& dir,
                     const StudyMeta& meta,
                     const std::function<void(const std::filesystem::path&)>& write_csv,
                     const nlohmann::json& summary,
                     const std::string& report_html);

/// Combines the shard directories of one study (every shard 1/n...n/n exactly once) into `out`:
/// the outputs the unsharded study writes. Throws std::runtime_error naming the directory and
/// what does not fit (another study, a shard missing or repeated, a unit missing).
void MergeStudies(const std::vector<std::filesystem::path>& dirs, const std::filesystem::path& out);

}  // namespace adahrs::proving
