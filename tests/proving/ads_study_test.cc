// The ADS study (calib/studies): the shipped ads_calibration sequence on truth-profile units (every
// effect on: hysteresis, die lag, converter noise). Checks that the in-memory run gives the
// calibration points its recording on disk gives, that a unit's result does not depend on the
// thread count, that shards merge into the unsharded study's files byte for byte, that a strategy
// whose temperature terms cannot follow the bridge (tolerance_minimax: the 10-term cubic's
// temperature order) yields less than the improved strategy, and that bad input is refused naming
// the file and JSON path. Under the sanitizers fewer units.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "calib/ads_calibration/ads_calibration_points.h"
#include "common/param_reader.h"
#include "hil/recording/recording_reader.h"
#include "proving/studies/ads_run_simulator.h"
#include "proving/studies/ads_study.h"
#include "proving/studies/ads_study_results.h"
#include "tests/proving/study_test_support.h"
#include "tests/support/ads_recording_sim.h"
#include "tests/support/xml_tree.h"

namespace adahrs::proving {
namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr int kUnits = 2;
#else
constexpr int kUnits = 4;
#endif

StudyDefinition Load(const std::string& name) { return testing::LoadTestStudy(name); }

struct AdsKind {
  static constexpr const char* kFirst = "ads_tolerance_minimax.json";
  static constexpr const char* kSecond = "ads_improved.json";
  static constexpr const char* kTempPrefix = "adahrs_ads_study_test_";
  static constexpr testing::StudyRunner kRun = RunAdsStudy;
  static StudySettings Settings() {
    StudySettings s;
    s.units = kUnits;
    s.seed = 20261128;
    return s;
  }
};

class AdsStudy : public testing::StudyFixture<AdsKind> {};

StudySettings Settings() { return AdsKind::Settings(); }

std::filesystem::path TempDir(const std::string& name) {
  return testing::StudyTempDir(AdsKind::kTempPrefix, name);
}

TEST(AdsRunSimulator, InMemoryRunGivesThePointsItsRecordingGives) {
  const auto params =
      sensor_sim::AdsUnitParams::Draw("ADS-0042", 42, sensor_sim::ModelProfile::kTruth);
  const auto dir = TempDir("recording");
  const std::string sequence = calib::testing::ShippedSequencePath("ads_calibration");
  calib::testing::WriteAdsRecording(dir, sequence, params, 43);
  const auto on_disk =
      calib::SelectAdsCalibrationPoints(hil::ReadRecording(dir), params.serial, dir.string());
  const hil::Recording in_memory =
      AdsRunRecording(calib::ParseSequenceFile(sequence).sequence, params, 43);
  const auto points = calib::SelectAdsCalibrationPoints(in_memory, params.serial, "memory");
  ASSERT_EQ(points.size(), on_disk.size());
  ASSERT_EQ(points.size(), 9u * (13 + 2 + 9));  // 9 temperatures x (13 + 2 altitudes, 9 speeds)
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(points[i].rows, 200);
    EXPECT_EQ(points[i].ps_cnt, on_disk[i].ps_cnt) << i;
    EXPECT_EQ(points[i].pt_temp_cnt, on_disk[i].pt_temp_cnt) << i;
    EXPECT_EQ(points[i].ps_ref_pa, on_disk[i].ps_ref_pa) << i;
    EXPECT_EQ(points[i].qc_ref_pa, on_disk[i].qc_ref_pa) << i;
    EXPECT_EQ(points[i].chamber_c, on_disk[i].chamber_c) << i;
  }
  std::filesystem::remove_all(dir);
}

TEST_F(AdsStudy, ResultsDoNotDependOnTheThreadCount) {
  EXPECT_EQ(MakeStudyMeta(*strategies_, Settings()).unit_kind, "ads");
  ASSERT_EQ(one_thread_->size(), static_cast<size_t>(kUnits));
  ExpectIndependentOfThreads(2);
}

TEST_F(AdsStudy, MergedShardsEqualTheUnshardedStudyByteForByte) { ExpectShardsMergeByteForByte(); }

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
  const nlohmann::json html = calib::testing::ParseXmlTree(dir / "report.html");
  ASSERT_FALSE(html.is_null());
  for (const char* id : {"settings", "yield", "paired", "altitude", "airspeed"}) {
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
  const nlohmann::json summary =
      nlohmann::json::parse(testing::ReadStudyFile(dir / "summary.json"));
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
}  // namespace adahrs::proving
