// Test helper shared by the IMU and ADS study tests: the study files of tests/data/studies, a
// fixture that runs a kind's two strategies once on one thread, and the checks every study meets
// (results independent of the thread count; shards merged into the unsharded study's files byte
// for byte). A kind names its study files, settings, runner and temporary-directory prefix:
//   struct Kind { static constexpr const char* kFirst, *kSecond, *kTempPrefix;
//                 static StudySettings Settings(); static constexpr StudyRunner kRun; };
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "adahrs_build_paths.h"
#include "proving/studies/study_results.h"

namespace adahrs::proving::testing {

using StudyRunner = std::vector<StudyUnitResult> (*)(const std::vector<StudyDefinition>&,
                                                     const StudySettings&,
                                                     int,
                                                     const StudyProgress&);

inline StudyDefinition LoadTestStudy(const std::string& name) {
  return LoadStudyDefinition(std::filesystem::path(ADAHRS_SOURCE_DIR) / "tests/data/studies" / name,
                             ADAHRS_SEQUENCE_DIR);
}

inline std::string ReadStudyFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// An empty path under the test's TMPDIR: <prefix><name>.
inline std::filesystem::path StudyTempDir(const std::string& prefix, const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / (prefix + name);
  std::filesystem::remove_all(dir);
  return dir;
}

template <typename Kind>
class StudyFixture : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    strategies_ =
        new std::vector<StudyDefinition>{LoadTestStudy(Kind::kFirst), LoadTestStudy(Kind::kSecond)};
    one_thread_ =
        new std::vector<StudyUnitResult>(Kind::kRun(*strategies_, Kind::Settings(), 1, {}));
  }
  static void TearDownTestSuite() {
    delete strategies_;
    delete one_thread_;
  }
  static std::filesystem::path TempDir(const std::string& name) {
    return StudyTempDir(Kind::kTempPrefix, name);
  }

  /// The one-thread results written and those of `threads` threads give the same files.
  static void ExpectIndependentOfThreads(int threads) {
    const auto dir1 = TempDir("threads1"), dir_n = TempDir("threads" + std::to_string(threads));
    const StudyMeta meta = MakeStudyMeta(*strategies_, Kind::Settings());
    WriteStudyOutputs(dir1, meta, *one_thread_);
    WriteStudyOutputs(dir_n, meta, Kind::kRun(*strategies_, Kind::Settings(), threads, {}));
    for (const char* file : {"results.csv", "summary.json"}) {
      EXPECT_EQ(ReadStudyFile(dir1 / file), ReadStudyFile(dir_n / file)) << file;
    }
    std::filesystem::remove_all(dir1);
    std::filesystem::remove_all(dir_n);
  }

  /// Shards 1/2 and 2/2, each run on two threads and merged (given in reverse), write what the
  /// unsharded study writes; a merge missing a shard is refused.
  static void ExpectShardsMergeByteForByte() {
    const auto whole = TempDir("whole"), merged = TempDir("merged");
    WriteStudyOutputs(whole, MakeStudyMeta(*strategies_, Kind::Settings()), *one_thread_);
    std::vector<std::filesystem::path> shards;
    for (int i = 1; i <= 2; ++i) {
      StudySettings s = Kind::Settings();
      s.shard = StudyShard::Parse(std::to_string(i) + "/2", "--shard");
      shards.push_back(TempDir("shard" + std::to_string(i)));
      const auto results = Kind::kRun(*strategies_, s, 2, {});
      for (const auto& r : results) EXPECT_EQ(r.index % 2, i - 1);
      WriteStudyOutputs(shards.back(), MakeStudyMeta(*strategies_, s), results);
    }
    MergeStudies({shards[1], shards[0]}, merged);
    for (const char* file : {"study.json", "results.csv", "summary.json", "report.html"}) {
      EXPECT_EQ(ReadStudyFile(whole / file), ReadStudyFile(merged / file)) << file;
    }
    EXPECT_THROW(MergeStudies({shards[0]}, merged), std::runtime_error);  // shard 2/2 missing
    for (const auto& d : shards) std::filesystem::remove_all(d);
    std::filesystem::remove_all(whole);
    std::filesystem::remove_all(merged);
  }

  static std::vector<StudyDefinition>* strategies_;
  static std::vector<StudyUnitResult>* one_thread_;
};

template <typename Kind>
std::vector<StudyDefinition>* StudyFixture<Kind>::strategies_ = nullptr;
template <typename Kind>
std::vector<StudyUnitResult>* StudyFixture<Kind>::one_thread_ = nullptr;

}  // namespace adahrs::proving::testing
