#include "proving/studies/study_results.h"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "common/unit_kind.h"
#include "proving/studies/ads_study_results.h"
#include "proving/studies/study_csv.h"
#include "proving/studies/study_report.h"

namespace adahrs::proving {
namespace {

using nlohmann::json;

constexpr const char* kCsvHeader =
    "unit_index,serial,draw_seed,noise_seed,strategy,fitted,worst_accel_mg,worst_rate_dps,"
    "accel_verdict,rate_verdict,pass_acceleration,pass_body_rate,pass_body_rate_limit,pass_all,"
    "failure";

std::string CsvOutcome(const StrategyOutcome& o) {
  return fmt::format("{},{},{},{},{},{},{},{},{},{}",
                     StudyCsvBool(o.fitted),
                     o.worst_accel_mg,
                     o.worst_rate_dps,
                     StudyCsvField(o.accel_verdict),
                     StudyCsvField(o.rate_verdict),
                     StudyCsvBool(o.pass_acceleration),
                     StudyCsvBool(o.pass_body_rate),
                     StudyCsvBool(o.pass_body_rate_limit),
                     StudyCsvBool(o.pass_all()),
                     StudyCsvField(o.failure));
}

StrategyOutcome OutcomeOf(const std::vector<std::string>& f) {
  StrategyOutcome o;
  o.fitted = f[5] == "1";
  o.worst_accel_mg = std::strtod(f[6].c_str(), nullptr);
  o.worst_rate_dps = std::strtod(f[7].c_str(), nullptr);
  o.accel_verdict = f[8];
  o.rate_verdict = f[9];
  o.pass_acceleration = f[10] == "1";
  o.pass_body_rate = f[11] == "1";
  o.pass_body_rate_limit = f[12] == "1";
  o.failure = f[14];
  return o;
}

const StudyCsvLayout kCsvLayout{kCsvHeader, 15, "study results", CsvOutcome, OutcomeOf};

bool PassAcceleration(const StrategyOutcome& o) { return o.pass_acceleration; }
bool PassBodyRate(const StrategyOutcome& o) { return o.pass_body_rate; }
bool PassBodyRateLimit(const StrategyOutcome& o) { return o.pass_body_rate_limit; }
bool PassAll(const StrategyOutcome& o) { return o.pass_all(); }
double WorstAccel(const StrategyOutcome& o) { return o.worst_accel_mg; }
double WorstRate(const StrategyOutcome& o) { return o.worst_rate_dps; }

StrategySummary SummariseStrategy(const StudyStrategyInfo& info,
                                  size_t s,
                                  const std::vector<StudyUnitResult>& results) {
  const StrategyTally t =
      TallyStrategy(results,
                    s,
                    {PassAcceleration, PassBodyRate, PassBodyRateLimit, PassAll},
                    {WorstAccel, WorstRate});
  StrategySummary out;
  out.info = info;
  out.units = t.units;
  out.fitted = t.fitted;
  out.yield_acceleration = t.yields[0];
  out.yield_body_rate = t.yields[1];
  out.yield_body_rate_limit = t.yields[2];
  out.yield_all = t.yields[3];
  out.worst_accel_mg = t.errors[0];
  out.worst_rate_dps = t.errors[1];
  return out;
}

PairedSummary SummarisePair(const StudyMeta& meta, const std::vector<StudyUnitResult>& results) {
  const std::vector<PairedInterval> i =
      PairedIntervals(results, meta.seed, {PassAll, PassAcceleration}, {WorstAccel, WorstRate});
  PairedSummary p;
  p.first = meta.strategies[0].name;
  p.second = meta.strategies[1].name;
  p.resamples = kStudyBootstrapResamples;
  p.yield_all = i[0];
  p.yield_acceleration = i[1];
  p.worst_accel_mg = i[2];
  p.worst_rate_dps = i[3];
  return p;
}

}  // namespace

json StudyStrategyInfo::ToJson() const {
  return {{"name", name},
          {"file", file},
          {"sequence", sequence},
          {"sequence_file", sequence_file},
          {"strategy", strategy},
          {"rig_time_s", rig_time_s}};
}

StudyStrategyInfo StudyStrategyInfo::FromJson(const json& j) {
  return {j.at("name"),
          j.at("file"),
          j.at("sequence"),
          j.at("sequence_file"),
          j.at("strategy"),
          j.at("rig_time_s")};
}

json StudyMeta::ToJson() const {
  json s = json::array();
  for (const auto& i : strategies) s.push_back(i.ToJson());
  json j = {{"format", "adahrs-study-run"},
            {"format_version", 1},
            {"units", units},
            {"seed", seed},
            {"population", population},
            {"g_local_mps2", g_local_mps2},
            {"evaluation_frames", evaluation_frames},
            {"strategies", s},
            {"shard", shard.Label()}};
  if (unit_kind != "imu") j["unit_kind"] = unit_kind;
  return j;
}

StudyMeta StudyMeta::Read(const std::filesystem::path& file) {
  try {
    const json j = json::parse(ReadStudyText(file));
    if (j.at("format") != "adahrs-study-run")
      throw std::runtime_error("$.format is not adahrs-study-run");
    StudyMeta m;
    m.unit_kind = j.value("unit_kind", "imu");
    m.units = j.at("units");
    m.seed = j.at("seed");
    m.population = j.at("population");
    m.g_local_mps2 = j.at("g_local_mps2");
    m.evaluation_frames = j.at("evaluation_frames");
    for (const json& s : j.at("strategies")) m.strategies.push_back(StudyStrategyInfo::FromJson(s));
    m.shard = StudyShard::Parse(j.at("shard").get<std::string>(), "$.shard");
    return m;
  } catch (const std::exception& e) {
    throw std::runtime_error(file.string() + ": " + e.what());
  }
}

bool StudyMeta::SameStudy(const StudyMeta& o) const {
  return unit_kind == o.unit_kind && units == o.units && seed == o.seed &&
         population == o.population && g_local_mps2 == o.g_local_mps2 &&
         evaluation_frames == o.evaluation_frames && strategies == o.strategies;
}

StudyMeta MakeStudyMeta(const std::vector<StudyDefinition>& strategies,
                        const StudySettings& settings) {
  StudyMeta m;
  if (!strategies.empty()) m.unit_kind = common::UnitKindName(strategies[0].unit_kind);
  m.units = settings.units;
  m.seed = settings.seed;
  m.population = settings.population.Label();
  m.g_local_mps2 = settings.g_local_mps2;
  m.evaluation_frames = settings.evaluation_frames;
  m.shard = settings.shard;
  for (const StudyDefinition& d : strategies) {
    m.strategies.push_back(
        {d.name, d.file, d.sequence.name, d.sequence_file, d.strategy_label, d.rig_time_s});
  }
  return m;
}

json StrategySummaryJson(const StudyStrategyInfo& info,
                         int units,
                         int fitted,
                         const json& yield,
                         const std::vector<std::pair<std::string, ErrorDistribution>>& errors) {
  json j = {{"name", info.name},
            {"strategy", info.strategy},
            {"sequence", info.sequence},
            {"rig_time_s", info.rig_time_s},
            {"units", units},
            {"fitted", fitted},
            {"yield", yield}};
  for (const auto& [name, e] : errors) j[name] = e.ToJson();
  return j;
}

json PairedSummaryJson(const std::string& first,
                       const std::string& second,
                       int resamples,
                       const std::vector<std::pair<std::string, PairedInterval>>& rows) {
  json j = {{"difference", second + " - " + first}, {"bootstrap_resamples", resamples}};
  for (const auto& [name, i] : rows) j[name] = i.ToJson();
  return j;
}

json StrategySummary::ToJson() const {
  return StrategySummaryJson(
      info,
      units,
      fitted,
      {{"acceleration", yield_acceleration},
       {"body_rate", yield_body_rate},
       {"body_rate_limit", yield_body_rate_limit},
       {"all", yield_all}},
      {{"worst_accel_mg", worst_accel_mg}, {"worst_rate_dps", worst_rate_dps}});
}

json PairedSummary::ToJson() const {
  return PairedSummaryJson(first,
                           second,
                           resamples,
                           {{"yield_all", yield_all},
                            {"yield_acceleration", yield_acceleration},
                            {"worst_accel_mg", worst_accel_mg},
                            {"worst_rate_dps", worst_rate_dps}});
}

json StudySummary::ToJson() const {
  json s = json::array();
  for (const auto& x : strategies) s.push_back(x.ToJson());
  json j = {{"units", units}, {"seed", seed}, {"population", population}, {"strategies", s}};
  if (paired) j["paired"] = paired->ToJson();
  return j;
}

StudySummary Summarise(const StudyMeta& meta, const std::vector<StudyUnitResult>& results) {
  StudySummary s;
  s.units = static_cast<int>(results.size());
  s.seed = meta.seed;
  s.population = meta.population;
  for (size_t i = 0; i < meta.strategies.size(); ++i) {
    s.strategies.push_back(SummariseStrategy(meta.strategies[i], i, results));
  }
  if (meta.strategies.size() == 2) s.paired = SummarisePair(meta, results);
  return s;
}

void WriteResultsCsv(const std::filesystem::path& file,
                     const StudyMeta& meta,
                     const std::vector<StudyUnitResult>& results) {
  WriteStudyCsv(file, meta, results, kCsvLayout);
}

std::vector<StudyUnitResult> ReadResultsCsv(const std::filesystem::path& file,
                                            const StudyMeta& meta) {
  if (meta.unit_kind == "ads") return ReadAdsResultsCsv(file, meta);
  return ReadStudyCsv(file, meta, kCsvLayout);
}

void WriteStudyOutputs(const std::filesystem::path& dir,
                       const StudyMeta& meta,
                       const std::vector<StudyUnitResult>& results) {
  if (meta.unit_kind == "ads") {
    WriteAdsStudyOutputs(dir, meta, results);
    return;
  }
  const StudySummary summary = Summarise(meta, results);
  WriteStudyFiles(
      dir,
      meta,
      [&](const std::filesystem::path& file) { WriteResultsCsv(file, meta, results); },
      summary.ToJson(),
      RenderStudyReport(meta, summary, results));
}

void WriteStudyFiles(const std::filesystem::path& dir,
                     const StudyMeta& meta,
                     const std::function<void(const std::filesystem::path&)>& write_csv,
                     const json& summary,
                     const std::string& report_html) {
  std::filesystem::create_directories(dir);
  WriteStudyText(dir / "study.json", meta.ToJson().dump(2) + "\n");
  write_csv(dir / "results.csv");
  WriteStudyText(dir / "summary.json", summary.dump(2) + "\n");
  WriteStudyText(dir / "report.html", report_html);
}

void MergeStudies(const std::vector<std::filesystem::path>& dirs,
                  const std::filesystem::path& out) {
  if (dirs.empty()) throw std::runtime_error("study merge: no shard directory given");
  const StudyMeta first = StudyMeta::Read(dirs[0] / "study.json");
  std::map<int, std::filesystem::path> shards;
  std::vector<StudyUnitResult> results;
  for (const auto& dir : dirs) {
    const StudyMeta meta = StudyMeta::Read(dir / "study.json");
    if (!meta.SameStudy(first)) {
      throw std::runtime_error(dir.string() + "/study.json: another study than " +
                               dirs[0].string() + "/study.json (settings or strategies differ)");
    }
    if (meta.shard.count != first.shard.count) {
      throw std::runtime_error(dir.string() + "/study.json: $.shard " + meta.shard.Label() +
                               " is not one of " + std::to_string(first.shard.count) + " shards");
    }
    if (!shards.emplace(meta.shard.index, dir).second) {
      throw std::runtime_error(dir.string() + "/study.json: $.shard " + meta.shard.Label() +
                               " is also " + shards[meta.shard.index].string());
    }
    for (StudyUnitResult& r : ReadResultsCsv(dir / "results.csv", meta)) {
      if (!meta.shard.Holds(r.index)) {
        throw std::runtime_error(dir.string() + "/results.csv: unit " + std::to_string(r.index) +
                                 " is not in shard " + meta.shard.Label());
      }
      results.push_back(std::move(r));
    }
  }
  for (int i = 1; i <= first.shard.count; ++i) {
    if (!shards.contains(i))
      throw std::runtime_error("study merge: shard " + std::to_string(i) + "/" +
                               std::to_string(first.shard.count) + " missing");
  }
  std::sort(results.begin(), results.end(), [](const auto& a, const auto& b) {
    return a.index < b.index;
  });
  for (int k = 0; k < std::max(first.units, static_cast<int>(results.size())); ++k) {
    if (k >= static_cast<int>(results.size()) || k >= first.units ||
        results[static_cast<size_t>(k)].index != k) {
      throw std::runtime_error("study merge: unit " + std::to_string(k) + " missing or repeated");
    }
  }
  StudyMeta merged = first;
  merged.shard = StudyShard{};
  WriteStudyOutputs(out, merged, results);
}

}  // namespace adahrs::proving
