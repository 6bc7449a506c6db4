#include "proving/studies/ads_study_results.h"

#include <cstdlib>

#include <fmt/format.h>

#include "proving/studies/ads_study_report.h"
#include "proving/studies/study_csv.h"

namespace adahrs::proving {
namespace {

using nlohmann::json;

constexpr const char* kCsvHeader =
    "unit_index,serial,draw_seed,noise_seed,strategy,fitted,worst_altitude_tol,"
    "worst_airspeed_tol,worst_altitude_no_history_tol,worst_airspeed_no_history_tol,"
    "altitude_failing_points,airspeed_failing_points,pass_altitude,pass_airspeed,pass_no_history,"
    "pass_all,failure";

std::string CsvOutcome(const StrategyOutcome& o) {
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}",
                     StudyCsvBool(o.fitted),
                     o.worst_altitude_tol,
                     o.worst_airspeed_tol,
                     o.worst_altitude_no_history_tol,
                     o.worst_airspeed_no_history_tol,
                     o.altitude_failing_points,
                     o.airspeed_failing_points,
                     StudyCsvBool(o.pass_altitude),
                     StudyCsvBool(o.pass_airspeed),
                     StudyCsvBool(o.pass_no_history),
                     StudyCsvBool(o.pass_ads_all()),
                     StudyCsvField(o.failure));
}

StrategyOutcome OutcomeOf(const std::vector<std::string>& f) {
  StrategyOutcome o;
  o.fitted = f[5] == "1";
  o.worst_altitude_tol = std::strtod(f[6].c_str(), nullptr);
  o.worst_airspeed_tol = std::strtod(f[7].c_str(), nullptr);
  o.worst_altitude_no_history_tol = std::strtod(f[8].c_str(), nullptr);
  o.worst_airspeed_no_history_tol = std::strtod(f[9].c_str(), nullptr);
  o.altitude_failing_points = std::stoi(f[10]);
  o.airspeed_failing_points = std::stoi(f[11]);
  o.pass_altitude = f[12] == "1";
  o.pass_airspeed = f[13] == "1";
  o.pass_no_history = f[14] == "1";
  o.failure = f[16];
  return o;
}

const StudyCsvLayout kCsvLayout{kCsvHeader, 17, "ADS study results", CsvOutcome, OutcomeOf};

bool PassAltitude(const StrategyOutcome& o) { return o.pass_altitude; }
bool PassAirspeed(const StrategyOutcome& o) { return o.pass_airspeed; }
bool PassNoHistory(const StrategyOutcome& o) { return o.pass_no_history; }
bool PassAll(const StrategyOutcome& o) { return o.pass_ads_all(); }
double WorstAltitude(const StrategyOutcome& o) { return o.worst_altitude_tol; }
double WorstAirspeed(const StrategyOutcome& o) { return o.worst_airspeed_tol; }

AdsStrategySummary SummariseStrategy(const StudyStrategyInfo& info,
                                     size_t s,
                                     const std::vector<StudyUnitResult>& results) {
  const StrategyTally t = TallyStrategy(results,
                                        s,
                                        {PassAltitude, PassAirspeed, PassNoHistory, PassAll},
                                        {WorstAltitude, WorstAirspeed});
  AdsStrategySummary out;
  out.info = info;
  out.units = t.units;
  out.fitted = t.fitted;
  out.yield_altitude = t.yields[0];
  out.yield_airspeed = t.yields[1];
  out.yield_no_history = t.yields[2];
  out.yield_all = t.yields[3];
  out.worst_altitude_tol = t.errors[0];
  out.worst_airspeed_tol = t.errors[1];
  return out;
}

AdsPairedSummary SummarisePair(const StudyMeta& meta, const std::vector<StudyUnitResult>& results) {
  const std::vector<PairedInterval> i = PairedIntervals(
      results, meta.seed, {PassAll, PassAltitude, PassAirspeed}, {WorstAltitude, WorstAirspeed});
  AdsPairedSummary p;
  p.first = meta.strategies[0].name;
  p.second = meta.strategies[1].name;
  p.resamples = kStudyBootstrapResamples;
  p.yield_all = i[0];
  p.yield_altitude = i[1];
  p.yield_airspeed = i[2];
  p.worst_altitude_tol = i[3];
  p.worst_airspeed_tol = i[4];
  return p;
}

}  // namespace

json AdsStrategySummary::ToJson() const {
  return StrategySummaryJson(
      info,
      units,
      fitted,
      {{"altitude", yield_altitude},
       {"airspeed", yield_airspeed},
       {"no_history", yield_no_history},
       {"all", yield_all}},
      {{"worst_altitude_tol", worst_altitude_tol}, {"worst_airspeed_tol", worst_airspeed_tol}});
}

json AdsPairedSummary::ToJson() const {
  return PairedSummaryJson(first,
                           second,
                           resamples,
                           {{"yield_all", yield_all},
                            {"yield_altitude", yield_altitude},
                            {"yield_airspeed", yield_airspeed},
                            {"worst_altitude_tol", worst_altitude_tol},
                            {"worst_airspeed_tol", worst_airspeed_tol}});
}

json AdsStudySummary::ToJson() const {
  json s = json::array();
  for (const auto& x : strategies) s.push_back(x.ToJson());
  json j = {{"unit_kind", "ads"},
            {"units", units},
            {"seed", seed},
            {"population", population},
            {"strategies", s}};
  if (paired) j["paired"] = paired->ToJson();
  return j;
}

AdsStudySummary SummariseAdsStudy(const StudyMeta& meta,
                                  const std::vector<StudyUnitResult>& results) {
  AdsStudySummary s;
  s.units = static_cast<int>(results.size());
  s.seed = meta.seed;
  s.population = meta.population;
  for (size_t i = 0; i < meta.strategies.size(); ++i) {
    s.strategies.push_back(SummariseStrategy(meta.strategies[i], i, results));
  }
  if (meta.strategies.size() == 2) s.paired = SummarisePair(meta, results);
  return s;
}

void WriteAdsResultsCsv(const std::filesystem::path& file,
                        const StudyMeta& meta,
                        const std::vector<StudyUnitResult>& results) {
  WriteStudyCsv(file, meta, results, kCsvLayout);
}

std::vector<StudyUnitResult> ReadAdsResultsCsv(const std::filesystem::path& file,
                                               const StudyMeta& meta) {
  return ReadStudyCsv(file, meta, kCsvLayout);
}

void WriteAdsStudyOutputs(const std::filesystem::path& dir,
                          const StudyMeta& meta,
                          const std::vector<StudyUnitResult>& results) {
  const AdsStudySummary summary = SummariseAdsStudy(meta, results);
  WriteStudyFiles(
      dir,
      meta,
      [&](const std::filesystem::path& file) { WriteAdsResultsCsv(file, meta, results); },
      summary.ToJson(),
      RenderAdsStudyReport(meta, summary, results));
}

}  // namespace adahrs::proving
