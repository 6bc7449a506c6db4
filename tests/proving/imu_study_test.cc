// The IMU study (calib/studies): a short sequence (tests/data/studies, 5 degC/min ramps over the
// envelope, 200 packets per acquisition) on nominal units. Checks that a unit's result does not
// depend on the thread count, that shards merge into the unsharded study's files byte for byte
// (study_test_support.h), that a thermal order of 0 yields less than the improved strategy, and
// that bad input is refused naming the file and JSON path (or the option). Under the sanitizers
// fewer units.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/param_reader.h"
#include "proving/studies/imu_study.h"
#include "proving/studies/study_results.h"
#include "tests/proving/study_test_support.h"
#include "tests/support/xml_tree.h"

namespace adahrs::proving {
namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr int kUnits = 2;
#else
constexpr int kUnits = 4;
#endif

StudyDefinition Load(const std::string& name) { return testing::LoadTestStudy(name); }

struct ImuKind {
  static constexpr const char* kFirst = "short_thermal_order0.json";
  static constexpr const char* kSecond = "short_improved.json";
  static constexpr const char* kTempPrefix = "adahrs_imu_study_test_";
  static constexpr testing::StudyRunner kRun = RunImuStudy;
  static StudySettings Settings() {
    StudySettings s;
    s.units = kUnits;
    s.seed = 20261127;
    s.population = {sensor_sim::ModelProfile::kNominal};
    return s;
  }
};

class ImuStudy : public testing::StudyFixture<ImuKind> {};

StudySettings Settings() { return ImuKind::Settings(); }

TEST_F(ImuStudy, ResultsDoNotDependOnTheThreadCount) {
  ASSERT_EQ(one_thread_->size(), static_cast<size_t>(kUnits));
  ExpectIndependentOfThreads(3);
}

TEST_F(ImuStudy, MergedShardsEqualTheUnshardedStudyByteForByte) { ExpectShardsMergeByteForByte(); }

TEST_F(ImuStudy, ThermalOrderZeroYieldsLessThanTheImprovedStrategy) {
  const StudySummary summary = Summarise(MakeStudyMeta(*strategies_, Settings()), *one_thread_);
  const StrategySummary& order0 = summary.strategies[0];
  const StrategySummary& improved = summary.strategies[1];
  std::printf("acceleration yield: order 0 %.2f, improved %.2f; median worst %.3f mg vs %.3f mg\n",
              order0.yield_acceleration,
              improved.yield_acceleration,
              order0.worst_accel_mg.p50,
              improved.worst_accel_mg.p50);
  EXPECT_EQ(improved.fitted, kUnits);
  EXPECT_EQ(improved.yield_acceleration, 1.0);  // nominal units: within 1.0 mg over the envelope
  EXPECT_EQ(order0.yield_acceleration, 0.0);    // the bias drift over 125 degC is left in
  ASSERT_TRUE(summary.paired.has_value());
  // docs/studies.md: the mean of the per-unit differences (improved - order 0) with its 95 %
  // percentile-bootstrap interval. The differences are taken here from the unit results; a
  // percentile interval of resampled means lies between the mean and the extreme differences.
  const PairedInterval& paired = summary.paired->worst_accel_mg;
  std::vector<double> diffs;
  for (const StudyUnitResult& r : *one_thread_)
    diffs.push_back(r.outcomes[1].worst_accel_mg - r.outcomes[0].worst_accel_mg);
  const auto [lowest, highest] = std::minmax_element(diffs.begin(), diffs.end());
  const double mean = std::accumulate(diffs.begin(), diffs.end(), 0.0) / kUnits;
  EXPECT_EQ(paired.units, kUnits);
  EXPECT_NEAR(paired.mean, mean, 1e-9 * std::abs(mean));
  EXPECT_GE(paired.ci95_low, *lowest);
  EXPECT_LE(paired.ci95_low, paired.mean);
  EXPECT_GE(paired.ci95_high, paired.mean);
  EXPECT_LE(paired.ci95_high, *highest);
  EXPECT_LT(paired.ci95_high, 0.0);  // improved - order 0 < 0 for sure
}

TEST_F(ImuStudy, ReportShowsTheYieldAndTheDistributionsOfEveryStrategy) {
  const auto dir = TempDir("report");
  WriteStudyOutputs(dir, MakeStudyMeta(*strategies_, Settings()), *one_thread_);
  const nlohmann::json html = calib::testing::ParseXmlTree(dir / "report.html");
  ASSERT_FALSE(html.is_null());
  for (const char* id : {"settings", "yield", "paired", "acceleration", "body-rate"}) {
    EXPECT_EQ(calib::testing::FindAll(html,
                                      [&](const nlohmann::json& n) {
                                        return n["tag"] == "section" &&
                                               n["attrib"].value("id", "") == id;
                                      })
                  .size(),
              1u)
        << id;
  }
  EXPECT_EQ(calib::testing::FindTag(html, "svg").size(), 4u);  // histogram and CDF per quantity
  // The yield table's acceleration column: order 0 passes no unit, the improved strategy all.
  std::map<std::string, double> accel_yield;
  for (const auto& row : calib::testing::FindTag(html, "tr")) {
    const auto cells = calib::testing::FindTag(row, "td");
    if (cells.size() == 13)
      accel_yield[cells[0]["text"]] = std::stod(cells[3]["text"].get<std::string>());
  }
  EXPECT_EQ(accel_yield["short_thermal_order0"], 0.0);
  EXPECT_EQ(accel_yield["short_improved"], 1.0);
  std::filesystem::remove_all(dir);
}

TEST(ImuStudyInput, UnknownStrategyIsRefusedNamingTheFileAndPath) {
  try {
    Load("unknown_strategy.json");
    FAIL() << "accepted an unknown strategy";
  } catch (const common::ParamError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("unknown_strategy.json"), std::string::npos) << what;
    EXPECT_NE(what.find("$.strategy"), std::string::npos) << what;
    EXPECT_NE(what.find("best_guess"), std::string::npos) << what;
  }
}

TEST(ImuStudyInput, SequenceTheValidatorRefusesIsRefusedNamingTheFileAndPath) {
  try {
    Load("refused_sequence.json");
    FAIL() << "accepted a sequence the validator refuses";
  } catch (const common::ParamError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("refused_sequence.json"), std::string::npos) << what;
    EXPECT_NE(what.find("$.sequence"), std::string::npos) << what;
    EXPECT_NE(what.find("$.steps[1].orientation"), std::string::npos) << what;
  }
}

TEST(ImuStudyInput, ShardBeyondItsCountIsRefusedNamingTheOption) {
  for (const std::string spec : {"3/2", "0/2", "1/0", "a/b", "2"}) {
    try {
      StudyShard::Parse(spec, "--shard");
      FAIL() << "accepted " << spec;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--shard \"" + spec + "\""), std::string::npos)
          << e.what();
    }
  }
  const StudyShard s = StudyShard::Parse("2/3", "--shard");
  EXPECT_FALSE(s.Holds(0));
  EXPECT_TRUE(s.Holds(1));
  EXPECT_TRUE(s.Holds(4));
}

}  // namespace
}  // namespace adahrs::proving
