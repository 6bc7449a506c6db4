// The ADS study (calib/studies): the shipped ads_calibration sequence on truth-profile units (every
// effect on: hysteresis, die lag, converter noise). Checks that the in-memory run gives the
// calibration points its recording on disk gives, that a unit's result does not depend on the
// thread count, that shards merge into the unsharded results.csv byte for byte, that a strategy
// whose temperature terms cannot follow the bridge (tolerance_minimax: the 10-term cubic's
// temperature order) yields less than the improved strategy, and that bad input is refused naming
// the file and JSON path. Under the sanitizers fewer units.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "adahrs_build_paths.h"
#include "calib/ads_calibration/ads_calibration_points.h"
#include "calib/studies/ads_run_simulator.h"
#include "calib/studies/ads_study.h"
#include "calib/studies/ads_study_results.h"
#include "common/param_reader.h"
#include "hil/recording/recording_reader.h"
#include "tests/calib/ads_recording_sim.h"
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
  s.seed = 20261128;
  return s;
}

std::string ReadFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::filesystem::path TempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("adahrs_ads_study_test_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

class AdsStudy : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    strategies_ = new std::vector<StudyDefinition>{Load("ads_tolerance_minimax.json"),
                                                   Load("ads_improved.json")};
    one_thread_ = new std::vector<StudyUnitResult>(RunAdsStudy(*strategies_, Settings(), 1));
  }
  static void TearDownTestSuite() {
    delete strategies_;
    delete one_thread_;
  }
  static std::vector<StudyDefinition>* strategies_;
  static std::vector<StudyUnitResult>* one_thread_;
};
std::vector<StudyDefinition>* AdsStudy::strategies_ = nullptr;
std::vector<StudyUnitResult>* AdsStudy::one_thread_ = nullptr;

TEST(AdsRunSimulator, InMemoryRunGivesThePointsItsRecordingGives) {
  const auto params =
      sensor_sim::AdsUnitParams::Draw("ADS-0042", 42, sensor_sim::ModelProfile::kTruth);
  const auto dir = TempDir("recording");
  const std::string sequence = testing::ShippedSequencePath("ads_calibration");
  testing::WriteAdsRecording(dir, sequence, params, 43);
  const auto on_disk =
      SelectAdsCalibrationPoints(hil::ReadRecording(dir), params.serial, dir.string());
  const hil::Recording in_memory =
      AdsRunRecording(ParseSequenceFile(sequence).sequence, params, 43);
  const auto points = SelectAdsCalibrationPoints(in_memory, params.serial, "memory");
  ASSERT_EQ(points.size(), on_disk.size());
  ASSERT_EQ(points.size(), 9u * (13 + 2 + 9));  // 9 temperatures x (13 + 2 altitudes, 9 speeds)
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(points[i].rows, 200);
    EXPECT_EQ(points[i].ps_code, on_disk[i].ps_code) << i;
    EXPECT_EQ(points[i].pt_temp_code, on_disk[i].pt_temp_code) << i;
    EXPECT_EQ(points[i].ps_ref_pa, on_disk[i].ps_ref_pa) << i;
    EXPECT_EQ(points[i].qc_ref_pa, on_disk[i].qc_ref_pa) << i;
    EXPECT_EQ(points[i].chamber_c, on_disk[i].chamber_c) << i;
  }
  std::filesystem::remove_all(dir);
}

TEST_F(AdsStudy, ResultsDoNotDependOnTheThreadCount) {
  const auto dir1 = TempDir("threads1"), dir2 = TempDir("threads2");
  const StudyMeta meta = MakeStudyMeta(*strategies_, Settings());
  EXPECT_EQ(meta.unit_kind, "ads");
  WriteStudyOutputs(dir1, meta, *one_thread_);
  WriteStudyOutputs(dir2, meta, RunAdsStudy(*strategies_, Settings(), 2));
  ASSERT_EQ(one_thread_->size(), static_cast<size_t>(kUnits));
  EXPECT_EQ(ReadFile(dir1 / "results.csv"), ReadFile(dir2 / "results.csv"));
  EXPECT_EQ(ReadFile(dir1 / "summary.json"), ReadFile(dir2 / "summary.json"));
  std::filesystem::remove_all(dir1);
  std::filesystem::remove_all(dir2);
}

TEST_F(AdsStudy, MergedShardsEqualTheUnshardedStudyByteForByte) {
  const auto whole = TempDir("whole"), merged = TempDir("merged");
  WriteStudyOutputs(whole, MakeStudyMeta(*strategies_, Settings()), *one_thread_);
  std::vector<std::filesystem::path> shards;
  for (int i = 1; i <= 2; ++i) {
    StudySettings s = Settings();
    s.shard = StudyShard::Parse(std::to_string(i) + "/2", "--shard");
    shards.push_back(TempDir("shard" + std::to_string(i)));
    const auto results = RunAdsStudy(*strategies_, s, 2);
    for (const auto& r : results) EXPECT_EQ(r.index % 2, i - 1);
    WriteStudyOutputs(shards.back(), MakeStudyMeta(*strategies_, s), results);
  }
  MergeStudies({shards[1], shards[0]}, merged);
  for (const char* file : {"study.json", "results.csv", "summary.json", "report.html"}) {
    EXPECT_EQ(ReadFile(whole / file), ReadFile(merged / file)) << file;
  }
  EXPECT_THROW(MergeStudies({shards[0]}, merged), std::runtime_error);  // shard 2/2 missing
  for (const auto& d : shards) std::filesystem::remove_all(d);
  std::filesystem::remove_all(whole);
  std::filesystem::remove_all(merged);
}

TEST_F(AdsStudy, CubicTemperatureOrderYieldsLessThanTheImprovedStrategy) {
  const AdsStudySummary summary =
      SummariseAdsStudy(MakeStudyMeta(*strategies_, Settings()), *one_thread_);
  const AdsStrategySummary& cubic = summary.strategies[0];
  const AdsStrategySummary& improved = summary.strategies[1];
  std::printf(
      "all yield: tolerance_minimax %.2f, improved %.2f; median worst altitude %.3f vs "
      "%.3f, airspeed %.3f vs %.3f tolerances\n",
      cubic.yield_all,
      improved.yield_all,
      cubic.worst_altitude_tol.p50,
      improved.worst_altitude_tol.p50,
      cubic.worst_airspeed_tol.p50,
      improved.worst_airspeed_tol.p50);
  EXPECT_EQ(improved.fitted, kUnits);
  EXPECT_EQ(improved.yield_all, 1.0);  // every grid point, every history (calibration-strategies)
  EXPECT_EQ(cubic.yield_all, 0.0);     // the bridge's temperature behaviour is left in
  ASSERT_TRUE(summary.paired.has_value());
  EXPECT_EQ(summary.paired->yield_all.mean, 1.0);
  EXPECT_LT(summary.paired->worst_altitude_tol.ci95_high, -1.0);  // improved - cubic, tolerances
  EXPECT_LT(summary.paired->worst_airspeed_tol.ci95_high, -1.0);
}

TEST_F(AdsStudy, ReportShowsTheYieldAndTheDistributionsOfEveryStrategy) {
  const auto dir = TempDir("report");
  WriteStudyOutputs(dir, MakeStudyMeta(*strategies_, Settings()), *one_thread_);
  const nlohmann::json html = testing::ParseXmlTree(dir / "report.html");
  ASSERT_FALSE(html.is_null());
  for (const char* id : {"settings", "yield", "paired", "altitude", "airspeed"}) {
    EXPECT_EQ(testing::FindAll(html,
                               [&](const nlohmann::json& n) {
                                 return n["tag"] == "section" && n["attrib"].value("id", "") == id;
                               })
                  .size(),
              1u)
        << id;
  }
  EXPECT_EQ(testing::FindTag(html, "svg").size(), 4u);  // histogram and CDF per quantity
  const nlohmann::json summary = nlohmann::json::parse(ReadFile(dir / "summary.json"));
  EXPECT_EQ(summary["unit_kind"], "ads");
  EXPECT_EQ(summary["strategies"][1]["yield"]["all"], 1.0);
  EXPECT_GT(summary["strategies"][1]["rig_time_s"].get<double>(), 3600.0);
  std::filesystem::remove_all(dir);
}

void ExpectRefused(const std::string& file, const std::string& path, const std::string& detail) {
  try {
    Load(file);
    FAIL() << "accepted " << file;
  } catch (const common::ParamError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file), std::string::npos) << what;
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(detail), std::string::npos) << what;
  }
}

TEST(AdsStudyInput, BadStudyFilesAreRefusedNamingTheFileAndPath) {
  ExpectRefused("ads_unknown_strategy.json", "$.strategy", "joint");
  ExpectRefused("ads_imu_sequence.json", "$.sequence", "not an ADS sequence");
  ExpectRefused("ads_unknown_kind.json", "$.unit_kind", "air_data");
}

}  // namespace
}  // namespace adahrs::calib
