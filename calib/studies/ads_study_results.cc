#include "calib/studies/ads_study_results.h"

#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "calib/studies/ads_study_report.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;

constexpr const char* kCsvHeader =
    "unit_index,serial,draw_seed,noise_seed,strategy,fitted,worst_altitude_tol,"
    "worst_airspeed_tol,worst_altitude_no_history_tol,worst_airspeed_no_history_tol,"
    "altitude_failing_points,airspeed_failing_points,pass_altitude,pass_airspeed,pass_no_history,"
    "pass_all,failure";
constexpr size_t kCsvColumns = 17;

std::string Bool(bool b) { return b ? "1" : "0"; }

AdsStrategySummary SummariseStrategy(const StudyStrategyInfo& info,
                                     size_t s,
                                     const std::vector<StudyUnitResult>& results) {
  AdsStrategySummary out;
  out.info = info;
  out.units = static_cast<int>(results.size());
  std::vector<double> altitude, airspeed;
  int pass_alt = 0, pass_cas = 0, pass_fresh = 0, pass_all = 0;
  for (const StudyUnitResult& r : results) {
    const StrategyOutcome& o = r.outcomes.at(s);
    out.fitted += o.fitted;
    pass_alt += o.pass_altitude;
    pass_cas += o.pass_airspeed;
    pass_fresh += o.pass_no_history;
    pass_all += o.pass_ads_all();
    altitude.push_back(o.worst_altitude_tol);
    airspeed.push_back(o.worst_airspeed_tol);
  }
  const double n = std::max<double>(1.0, static_cast<double>(results.size()));
  out.yield_altitude = pass_alt / n;
  out.yield_airspeed = pass_cas / n;
  out.yield_no_history = pass_fresh / n;
  out.yield_all = pass_all / n;
  out.worst_altitude_tol = StudyDistribution(altitude);
  out.worst_airspeed_tol = StudyDistribution(airspeed);
  return out;
}

double Difference(bool second, bool first) {
  return static_cast<double>(second) - static_cast<double>(first);
}

AdsPairedSummary SummarisePair(const StudyMeta& meta, const std::vector<StudyUnitResult>& results) {
  AdsPairedSummary p;
  p.first = meta.strategies[0].name;
  p.second = meta.strategies[1].name;
  p.resamples = kStudyBootstrapResamples;
  std::vector<double> pass, pass_alt, pass_cas, altitude, airspeed;
  for (const StudyUnitResult& r : results) {
    const StrategyOutcome& a = r.outcomes[0];
    const StrategyOutcome& b = r.outcomes[1];
    pass.push_back(Difference(b.pass_ads_all(), a.pass_ads_all()));
    pass_alt.push_back(Difference(b.pass_altitude, a.pass_altitude));
    pass_cas.push_back(Difference(b.pass_airspeed, a.pass_airspeed));
    if (a.fitted && b.fitted) {
      altitude.push_back(b.worst_altitude_tol - a.worst_altitude_tol);
      airspeed.push_back(b.worst_airspeed_tol - a.worst_airspeed_tol);
    }
  }
  p.yield_all = StudyBootstrap(pass, meta.seed);
  p.yield_altitude = StudyBootstrap(pass_alt, meta.seed + 1);
  p.yield_airspeed = StudyBootstrap(pass_cas, meta.seed + 2);
  p.worst_altitude_tol = StudyBootstrap(altitude, meta.seed + 3);
  p.worst_airspeed_tol = StudyBootstrap(airspeed, meta.seed + 4);
  return p;
}

std::string CsvRow(const StudyUnitResult& r,
                   const std::string& strategy,
                   const StrategyOutcome& o) {
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                     r.index,
                     r.serial,
                     r.draw_seed,
                     r.noise_seed,
                     StudyCsvField(strategy),
                     Bool(o.fitted),
                     o.worst_altitude_tol,
                     o.worst_airspeed_tol,
                     o.worst_altitude_no_history_tol,
                     o.worst_airspeed_no_history_tol,
                     o.altitude_failing_points,
                     o.airspeed_failing_points,
                     Bool(o.pass_altitude),
                     Bool(o.pass_airspeed),
                     Bool(o.pass_no_history),
                     Bool(o.pass_ads_all()),
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

}  // namespace

json AdsStrategySummary::ToJson() const {
  return {{"name", info.name},
          {"strategy", info.strategy},
          {"sequence", info.sequence},
          {"rig_time_s", info.rig_time_s},
          {"units", units},
          {"fitted", fitted},
          {"yield",
           {{"altitude", yield_altitude},
            {"airspeed", yield_airspeed},
            {"no_history", yield_no_history},
            {"all", yield_all}}},
          {"worst_altitude_tol", worst_altitude_tol.ToJson()},
          {"worst_airspeed_tol", worst_airspeed_tol.ToJson()}};
}

json AdsPairedSummary::ToJson() const {
  return {{"difference", second + " - " + first},
          {"bootstrap_resamples", resamples},
          {"yield_all", yield_all.ToJson()},
          {"yield_altitude", yield_altitude.ToJson()},
          {"yield_airspeed", yield_airspeed.ToJson()},
          {"worst_altitude_tol", worst_altitude_tol.ToJson()},
          {"worst_airspeed_tol", worst_airspeed_tol.ToJson()}};
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
  std::string text = std::string(kCsvHeader) + "\n";
  for (const StudyUnitResult& r : results) {
    for (size_t s = 0; s < meta.strategies.size(); ++s) {
      text += CsvRow(r, meta.strategies[s].name, r.outcomes.at(s));
    }
  }
  WriteStudyText(file, text);
}

std::vector<StudyUnitResult> ReadAdsResultsCsv(const std::filesystem::path& file,
                                               const StudyMeta& meta) {
  std::istringstream in(ReadStudyText(file));
  std::string line;
  if (!std::getline(in, line) || line != kCsvHeader) {
    throw std::runtime_error(file.string() + " line 1: not the ADS study results header");
  }
  std::vector<StudyUnitResult> results;
  for (int n = 2; std::getline(in, line); ++n) {
    const std::vector<std::string> f = StudyCsvSplit(line);
    const size_t s = (n - 2) % meta.strategies.size();
    auto fail = [&](size_t column, const std::string& why) {
      throw std::runtime_error(file.string() + " line " + std::to_string(n) + " column " +
                               std::to_string(column + 1) + ": " + why);
    };
    if (f.size() != kCsvColumns) fail(0, "expected " + std::to_string(kCsvColumns) + " fields");
    if (f[4] != meta.strategies[s].name) fail(4, "expected strategy " + meta.strategies[s].name);
    try {
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
      results.back().outcomes.push_back(OutcomeOf(f));
    } catch (const std::logic_error& e) {  // std::stoi and friends
      fail(0, std::string("not a number where one is expected (") + e.what() + ")");
    }
  }
  return results;
}

void WriteAdsStudyOutputs(const std::filesystem::path& dir,
                          const StudyMeta& meta,
                          const std::vector<StudyUnitResult>& results) {
  std::filesystem::create_directories(dir);
  const AdsStudySummary summary = SummariseAdsStudy(meta, results);
  WriteStudyText(dir / "study.json", meta.ToJson().dump(2) + "\n");
  WriteAdsResultsCsv(dir / "results.csv", meta, results);
  WriteStudyText(dir / "summary.json", summary.ToJson().dump(2) + "\n");
  WriteStudyText(dir / "report.html", RenderAdsStudyReport(meta, summary, results));
}

}  // namespace adahrs::calib
