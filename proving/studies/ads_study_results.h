// What an ADS study writes (docs/studies.md "ADS studies"), beside the IMU study's files of the
// same names: results.csv with the ADS criteria's columns, summary.json with the yield per
// criterion (altitude, airspeed, no_history, all), the distributions of the worst errors in
// tolerances, rig time and, with two strategies, the paired differences second − first with
// bootstrap 95 % intervals; report.html. study.json is the IMU study's with "unit_kind": "ads".
// As for IMU studies the summary is a function of study.json and results.csv alone, so merged
// shards summarise exactly as the unsharded study. Reading errors throw std::runtime_error naming
// the file, line and column.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "proving/studies/study_results.h"

namespace adahrs::proving {

struct AdsStrategySummary {
  StudyStrategyInfo info;
  int units = 0;
  int fitted = 0;
  double yield_altitude = 0.0;  ///< fraction of units passing
  double yield_airspeed = 0.0;
  double yield_no_history = 0.0;  ///< informative (StrategyOutcome::pass_no_history)
  double yield_all = 0.0;
  ErrorDistribution worst_altitude_tol;  ///< worst |error| / tolerance, every history
  ErrorDistribution worst_airspeed_tol;
  nlohmann::json ToJson() const;
};

struct AdsPairedSummary {
  std::string first, second;
  int resamples = 0;
  PairedInterval yield_all;  ///< pass (1/0) second − first, every unit
  PairedInterval yield_altitude;
  PairedInterval yield_airspeed;
  PairedInterval worst_altitude_tol;  ///< second − first, units both fitted
  PairedInterval worst_airspeed_tol;
  nlohmann::json ToJson() const;
};

struct AdsStudySummary {
  int units = 0;
  uint64_t seed = 0;
  std::string population;
  std::vector<AdsStrategySummary> strategies;
  std::optional<AdsPairedSummary> paired;
  nlohmann::json ToJson() const;
};

AdsStudySummary SummariseAdsStudy(const StudyMeta& meta,
                                  const std::vector<StudyUnitResult>& results);

void WriteAdsResultsCsv(const std::filesystem::path& file,
                        const StudyMeta& meta,
                        const std::vector<StudyUnitResult>& results);
std::vector<StudyUnitResult> ReadAdsResultsCsv(const std::filesystem::path& file,
                                               const StudyMeta& meta);

/// Writes study.json, results.csv, summary.json and report.html into `dir`.
void WriteAdsStudyOutputs(const std::filesystem::path& dir,
                          const StudyMeta& meta,
                          const std::vector<StudyUnitResult>& results);

}  // namespace adahrs::proving
