// The IMU study (calib/studies): a short sequence (tests/data/studies, 5 degC/min ramps over the
// envelope, 200 packets per acquisition) on nominal units. Checks that a unit's result does not
// depend on the thread count, that shards merge into the unsharded results.csv byte for byte,
// that a thermal order of 0 yields less than the improved strategy, and that bad input is refused
// naming the file and JSON path (or the option). Under the sanitizers fewer units.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "adahrs_build_paths.h"
#include "calib/studies/imu_study.h"
#include "calib/studies/study_results.h"
#include "common/param_reader.h"
#include "tests/calib/xml_tree.h"

namespace adahrs::calib {
namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr int kUnits = 2;
#else
constexpr int kUnits = 4;
#endif

const std::filesystem::path kData = std::filesystem::path(ADAHRS_SOURCE_DIR) / "tests/data/studies";

StudyDefinition Load(const std::string& name) {
  return LoadStudyDefinition(kData / name, ADAHRS_SEQUENCE_DIR);
}

StudySettings Settings() {
  StudySettings s;
  s.units = kUnits;
  s.seed = 20261127;
  s.population = {sensor_sim::ModelProfile::kNominal};
  return s;
}

std::string ReadFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::filesystem::path TempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("adahrs_imu_study_test_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

class ImuStudy : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    strategies_ = new std::vector<StudyDefinition>{Load("short_thermal_order0.json"),
                                                   Load("short_improved.json")};
    one_thread_ = new std::vector<StudyUnitResult>(RunImuStudy(*strategies_, Settings(), 1));
  }
  static void TearDownTestSuite() {
    delete strategies_;
    delete one_thread_;
  }
  static std::vector<StudyDefinition>* strategies_;
  static std::vector<StudyUnitResult>* one_thread_;
};
std::vector<StudyDefinition>* ImuStudy::strategies_ = nullptr;
std::vector<StudyUnitResult>* ImuStudy::one_thread_ = nullptr;

TEST_F(ImuStudy, ResultsDoNotDependOnTheThreadCount) {
  const auto dir1 = TempDir("threads1"), dir3 = TempDir("threads3");
  const StudyMeta meta = MakeStudyMeta(*strategies_, Settings());
  WriteStudyOutputs(dir1, meta, *one_thread_);
  WriteStudyOutputs(dir3, meta, RunImuStudy(*strategies_, Settings(), 3));
  ASSERT_EQ(one_thread_->size(), static_cast<size_t>(kUnits));
  EXPECT_EQ(ReadFile(dir1 / "results.csv"), ReadFile(dir3 / "results.csv"));
  EXPECT_EQ(ReadFile(dir1 / "summary.json"), ReadFile(dir3 / "summary.json"));
  std::filesystem::remove_all(dir1);
  std::filesystem::remove_all(dir3);
}

TEST_F(ImuStudy, MergedShardsEqualTheUnshardedStudyByteForByte) {
  const auto whole = TempDir("whole"), merged = TempDir("merged");
  WriteStudyOutputs(whole, MakeStudyMeta(*strategies_, Settings()), *one_thread_);
  std::vector<std::filesystem::path> shards;
  for (int i = 1; i <= 2; ++i) {
    StudySettings s = Settings();
    s.shard = StudyShard::Parse(std::to_string(i) + "/2", "--shard");
    shards.push_back(TempDir("shard" + std::to_string(i)));
    const auto results = RunImuStudy(*strategies_, s, 2);
    for (const auto& r : results) EXPECT_EQ(r.index % 2, i - 1);
    WriteStudyOutputs(shards.back(), MakeStudyMeta(*strategies_, s), results);
  }
  MergeStudies({shards[1], shards[0]}, merged);
  EXPECT_EQ(ReadFile(whole / "results.csv"), ReadFile(merged / "results.csv"));
  EXPECT_EQ(ReadFile(whole / "summary.json"), ReadFile(merged / "summary.json"));
  EXPECT_THROW(MergeStudies({shards[0]}, merged), std::runtime_error);  // shard 2/2 missing
  for (const auto& d : shards) std::filesystem::remove_all(d);
  std::filesystem::remove_all(whole);
  std::filesystem::remove_all(merged);
}

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
  EXPECT_GT(summary.paired->worst_accel_mg.ci95_low, -1e9);
  EXPECT_LT(summary.paired->worst_accel_mg.ci95_high, 0.0);  // improved - order 0 < 0 for sure
}

TEST_F(ImuStudy, ReportShowsTheYieldAndTheDistributionsOfEveryStrategy) {
  const auto dir = TempDir("report");
  WriteStudyOutputs(dir, MakeStudyMeta(*strategies_, Settings()), *one_thread_);
  const nlohmann::json html = testing::ParseXmlTree(dir / "report.html");
  ASSERT_FALSE(html.is_null());
  for (const char* id : {"settings", "yield", "paired", "acceleration", "body-rate"}) {
    EXPECT_EQ(testing::FindAll(html,
                               [&](const nlohmann::json& n) {
                                 return n["tag"] == "section" && n["attrib"].value("id", "") == id;
                               })
                  .size(),
              1u)
        << id;
  }
  EXPECT_EQ(testing::FindTag(html, "svg").size(), 4u);  // histogram and CDF per quantity
  // The yield table's acceleration column: order 0 passes no unit, the improved strategy all.
  std::map<std::string, double> accel_yield;
  for (const auto& row : testing::FindTag(html, "tr")) {
    const auto cells = testing::FindTag(row, "td");
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
}  // namespace adahrs::calib
