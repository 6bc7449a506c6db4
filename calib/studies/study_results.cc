#include "calib/studies/study_results.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "calib/studies/ads_study_results.h"
#include "calib/studies/study_report.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;

constexpr int kBootstrapResamples = kStudyBootstrapResamples;
constexpr const char* kCsvHeader =
    "unit_index,serial,draw_seed,noise_seed,strategy,fitted,worst_accel_mg,worst_rate_dps,"
    "accel_verdict,rate_verdict,pass_acceleration,pass_body_rate,pass_body_rate_limit,pass_all,"
    "failure";
constexpr size_t kCsvColumns = 15;

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// Splits one CSV line (RFC 4180 quoting, no line breaks inside fields).
std::vector<std::string> CsvSplit(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

std::string Bool(bool b) { return b ? "1" : "0"; }

ErrorDistribution Distribution(std::vector<double> values) {
  std::erase_if(values, [](double v) { return !std::isfinite(v); });
  ErrorDistribution d;
  d.count = static_cast<int>(values.size());
  if (values.empty()) {
    d.mean = d.p50 = d.p90 = d.p95 = d.p99 = d.max = std::numeric_limits<double>::quiet_NaN();
    return d;
  }
  std::sort(values.begin(), values.end());
  auto rank = [&](double p) {
    const auto k = static_cast<size_t>(std::ceil(p * static_cast<double>(values.size())));
    return values[std::max<size_t>(k, 1) - 1];
  };
  double sum = 0.0;
  for (double v : values) sum += v;
  d.mean = sum / static_cast<double>(values.size());
  d.p50 = rank(0.50);
  d.p90 = rank(0.90);
  d.p95 = rank(0.95);
  d.p99 = rank(0.99);
  d.max = values.back();
  return d;
}

// Mean of `diffs` with the percentile bootstrap (resampling units with replacement).
PairedInterval Bootstrap(const std::vector<double>& diffs, uint64_t seed) {
  PairedInterval p;
  p.units = static_cast<int>(diffs.size());
  if (diffs.empty()) {
    p.mean = p.ci95_low = p.ci95_high = std::numeric_limits<double>::quiet_NaN();
    return p;
  }
  double sum = 0.0;
  for (double d : diffs) sum += d;
  p.mean = sum / static_cast<double>(diffs.size());
  std::mt19937_64 rng(seed);
  std::vector<double> means(kBootstrapResamples);
  for (double& m : means) {
    double s = 0.0;
    for (size_t i = 0; i < diffs.size(); ++i) s += diffs[rng() % diffs.size()];
    m = s / static_cast<double>(diffs.size());
  }
  std::sort(means.begin(), means.end());
  p.ci95_low = means[static_cast<size_t>(0.025 * kBootstrapResamples)];
  p.ci95_high = means[static_cast<size_t>(0.975 * kBootstrapResamples) - 1];
  return p;
}

StrategySummary SummariseStrategy(const StudyStrategyInfo& info,
                                  size_t s,
                                  const std::vector<StudyUnitResult>& results) {
  StrategySummary out;
  out.info = info;
  out.units = static_cast<int>(results.size());
  std::vector<double> accel, rate;
  int pass_a = 0, pass_r = 0, pass_limit = 0, pass_all = 0;
  for (const StudyUnitResult& r : results) {
    const StrategyOutcome& o = r.outcomes.at(s);
    out.fitted += o.fitted;
    pass_a += o.pass_acceleration;
    pass_r += o.pass_body_rate;
    pass_limit += o.pass_body_rate_limit;
    pass_all += o.pass_all();
    accel.push_back(o.worst_accel_mg);
    rate.push_back(o.worst_rate_dps);
  }
  const double n = std::max<double>(1.0, static_cast<double>(results.size()));
  out.yield_acceleration = pass_a / n;
  out.yield_body_rate = pass_r / n;
  out.yield_body_rate_limit = pass_limit / n;
  out.yield_all = pass_all / n;
  out.worst_accel_mg = Distribution(accel);
  out.worst_rate_dps = Distribution(rate);
  return out;
}

PairedSummary SummarisePair(const StudyMeta& meta, const std::vector<StudyUnitResult>& results) {
  PairedSummary p;
  p.first = meta.strategies[0].name;
  p.second = meta.strategies[1].name;
  p.resamples = kBootstrapResamples;
  std::vector<double> pass, pass_accel, accel, rate;
  for (const StudyUnitResult& r : results) {
    const StrategyOutcome& a = r.outcomes[0];
    const StrategyOutcome& b = r.outcomes[1];
    pass.push_back(static_cast<double>(b.pass_all()) - static_cast<double>(a.pass_all()));
    pass_accel.push_back(static_cast<double>(b.pass_acceleration) -
                         static_cast<double>(a.pass_acceleration));
    if (a.fitted && b.fitted) {
      accel.push_back(b.worst_accel_mg - a.worst_accel_mg);
      rate.push_back(b.worst_rate_dps - a.worst_rate_dps);
    }
  }
  p.yield_all = Bootstrap(pass, meta.seed);
  p.yield_acceleration = Bootstrap(pass_accel, meta.seed + 1);
  p.worst_accel_mg = Bootstrap(accel, meta.seed + 2);
  p.worst_rate_dps = Bootstrap(rate, meta.seed + 3);
  return p;
}

std::string ReadText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot be read");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void WriteText(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(file.string() + ": cannot be written");
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
    const json j = json::parse(ReadText(file));
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
  if (!strategies.empty() && strategies[0].unit_kind == UnitKind::kAds) m.unit_kind = "ads";
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

json ErrorDistribution::ToJson() const {
  return {{"count", count},
          {"mean", mean},
          {"p50", p50},
          {"p90", p90},
          {"p95", p95},
          {"p99", p99},
          {"max", max}};
}

json StrategySummary::ToJson() const {
  return {{"name", info.name},
          {"strategy", info.strategy},
          {"sequence", info.sequence},
          {"rig_time_s", info.rig_time_s},
          {"units", units},
          {"fitted", fitted},
          {"yield",
           {{"acceleration", yield_acceleration},
            {"body_rate", yield_body_rate},
            {"body_rate_limit", yield_body_rate_limit},
            {"all", yield_all}}},
          {"worst_accel_mg", worst_accel_mg.ToJson()},
          {"worst_rate_dps", worst_rate_dps.ToJson()}};
}

json PairedInterval::ToJson() const {
  return {{"units", units}, {"mean", mean}, {"ci95_low", ci95_low}, {"ci95_high", ci95_high}};
}

json PairedSummary::ToJson() const {
  return {{"difference", second + " - " + first},
          {"bootstrap_resamples", resamples},
          {"yield_all", yield_all.ToJson()},
          {"yield_acceleration", yield_acceleration.ToJson()},
          {"worst_accel_mg", worst_accel_mg.ToJson()},
          {"worst_rate_dps", worst_rate_dps.ToJson()}};
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
  std::string text = std::string(kCsvHeader) + "\n";
  for (const StudyUnitResult& r : results) {
    for (size_t s = 0; s < meta.strategies.size(); ++s) {
      const StrategyOutcome& o = r.outcomes.at(s);
      text += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                          r.index,
                          r.serial,
                          r.draw_seed,
                          r.noise_seed,
                          CsvField(meta.strategies[s].name),
                          Bool(o.fitted),
                          o.worst_accel_mg,
                          o.worst_rate_dps,
                          CsvField(o.accel_verdict),
                          CsvField(o.rate_verdict),
                          Bool(o.pass_acceleration),
                          Bool(o.pass_body_rate),
                          Bool(o.pass_body_rate_limit),
                          Bool(o.pass_all()),
                          CsvField(o.failure));
    }
  }
  WriteText(file, text);
}

std::vector<StudyUnitResult> ReadResultsCsv(const std::filesystem::path& file,
                                            const StudyMeta& meta) {
  if (meta.unit_kind == "ads") return ReadAdsResultsCsv(file, meta);
  std::istringstream in(ReadText(file));
  std::string line;
  if (!std::getline(in, line) || line != kCsvHeader) {
    throw std::runtime_error(file.string() + " line 1: not the study results header");
  }
  std::vector<StudyUnitResult> results;
  for (int n = 2; std::getline(in, line); ++n) {
    const std::vector<std::string> f = CsvSplit(line);
    const size_t s = (n - 2) % meta.strategies.size();
    auto fail = [&](size_t column, const std::string& why) {
      throw std::runtime_error(file.string() + " line " + std::to_string(n) + " column " +
                               std::to_string(column + 1) + ": " + why);
    };
    if (f.size() != kCsvColumns) fail(0, "expected " + std::to_string(kCsvColumns) + " fields");
    if (f[4] != meta.strategies[s].name) fail(4, "expected strategy " + meta.strategies[s].name);
    if (s == 0) {
      StudyUnitResult r;
      r.index = std::stoi(f[0]);
      r.serial = f[1];
      r.draw_seed = std::stoull(f[2]);
      r.noise_seed = std::stoull(f[3]);
      results.push_back(r);
    } else if (std::stoi(f[0]) != results.back().index) {
      fail(0, "expected unit " + std::to_string(results.back().index));
    }
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
    results.back().outcomes.push_back(o);
  }
  return results;
}

void WriteStudyOutputs(const std::filesystem::path& dir,
                       const StudyMeta& meta,
                       const std::vector<StudyUnitResult>& results) {
  if (meta.unit_kind == "ads") {
    WriteAdsStudyOutputs(dir, meta, results);
    return;
  }
  std::filesystem::create_directories(dir);
  const StudySummary summary = Summarise(meta, results);
  WriteText(dir / "study.json", meta.ToJson().dump(2) + "\n");
  WriteResultsCsv(dir / "results.csv", meta, results);
  WriteText(dir / "summary.json", summary.ToJson().dump(2) + "\n");
  WriteText(dir / "report.html", RenderStudyReport(meta, summary, results));
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

ErrorDistribution StudyDistribution(std::vector<double> values) {
  return Distribution(std::move(values));
}

PairedInterval StudyBootstrap(const std::vector<double>& diffs, uint64_t seed) {
  return Bootstrap(diffs, seed);
}

std::string StudyCsvField(const std::string& text) { return CsvField(text); }

std::vector<std::string> StudyCsvSplit(const std::string& line) { return CsvSplit(line); }

std::string ReadStudyText(const std::filesystem::path& file) { return ReadText(file); }

void WriteStudyText(const std::filesystem::path& file, const std::string& text) {
  WriteText(file, text);
}

}  // namespace adahrs::calib
