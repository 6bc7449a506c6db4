// Constants against the recordings they were fitted on: unchanged, changed since the fit (refused
// by download and records, flagged by the report), or not readable on this machine (a note).
#include "calib/constants/provenance_check.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/constants/recording_checksum.h"

namespace adahrs::calib {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

TEST(ProvenanceCheck, UnchangedChangedAndUnreadableRecordings) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("adahrs_provenance_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "run");
  std::ofstream(dir / "run" / "meta.json") << "{}";
  std::ofstream(dir / "run" / "imu.csv") << "t_s\n";
  std::ofstream(dir / "run" / "ads.csv") << "t_s\n";
  ConstantsFile file;
  file.serial = "IMU-0001";
  file.provenance.recordings = {{(dir / "run").string(), RecordingSha256(dir / "run")},
                                {(dir / "elsewhere").string(), std::string(64, 'a')}};

  std::vector<RecordingCheck> checks = RequireUnchangedRecordings(file, "IMU-0001.json");
  ASSERT_EQ(checks.size(), 2u);
  EXPECT_FALSE(checks[0].changed());
  EXPECT_THAT(checks[0].Describe(), HasSubstr("unchanged since the fit"));
  EXPECT_FALSE(checks[1].current_sha256.has_value());
  EXPECT_THAT(checks[1].Describe(), HasSubstr("not checked, no such run directory here"));

  std::ofstream(dir / "run" / "imu.csv", std::ios::app) << "0.01\n";  // one row more since the fit
  checks = CheckRecordings(file.provenance);
  EXPECT_TRUE(checks[0].changed());
  try {
    RequireUnchangedRecordings(file, "IMU-0001.json");
    FAIL() << "a changed recording was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(),
                AllOf(HasSubstr("IMU-0001.json"),
                      HasSubstr((dir / "run").string()),
                      HasSubstr("CHANGED since the fit"),
                      HasSubstr(file.provenance.recordings[0].sha256)));
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace adahrs::calib
