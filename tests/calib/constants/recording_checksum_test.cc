// RecordingSha256 against an independent implementation: Python's hashlib over the same three
// files concatenated (the contract: meta.json, imu.csv, ads.csv in that order).
#include "calib/constants/recording_checksum.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace adahrs::calib {
namespace {

std::string RunCommand(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return out;
  char buffer[256];
  while (fgets(buffer, sizeof buffer, pipe)) out += buffer;
  pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  return out;
}

TEST(RecordingChecksum, MatchesHashlibOverTheThreeFiles) {
  const auto dir = std::filesystem::temp_directory_path() / "adahrs_checksum_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "meta.json") << "{\"format_version\": 2}\n";
  std::string big;
  for (int i = 0; i < 20000; ++i) big += std::to_string(i * 7919) + ",row\n";  // > one 64 KiB read
  std::ofstream(dir / "imu.csv") << "t_s,unit\n" << big;
  std::ofstream(dir / "ads.csv") << "t_s,unit\n";
  std::ofstream(dir / "not_covered.txt") << "ignored";
  const std::string expected =
      RunCommand(std::string(ADAHRS_PYTHON) + " -c \"import hashlib,sys; d='" + dir.string() +
                 "'; print(hashlib.sha256(b''.join(open(d+'/'+n,'rb').read() for n in "
                 "('meta.json','imu.csv','ads.csv'))).hexdigest())\"");
  ASSERT_EQ(expected.size(), 64u) << expected;
  EXPECT_EQ(RecordingSha256(dir), expected);
  // One byte more anywhere changes it.
  std::ofstream(dir / "ads.csv", std::ios::app) << "x";
  EXPECT_NE(RecordingSha256(dir), expected);
  std::filesystem::remove_all(dir);
}

// The checksum is kept per run directory between calls; a file rewritten in place at the same
// size (a new modification time) is read again.
TEST(RecordingChecksum, AFileRewrittenInPlaceIsHashedAgain) {
  const auto dir = std::filesystem::temp_directory_path() / "adahrs_checksum_rewrite";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "meta.json") << "{}";
  std::ofstream(dir / "imu.csv") << "t_s\n0.01\n";
  std::ofstream(dir / "ads.csv") << "t_s\n";
  const auto old = std::filesystem::file_time_type::clock::now() - std::chrono::hours(1);
  for (const char* name : {"meta.json", "imu.csv", "ads.csv"}) {
    std::filesystem::last_write_time(dir / name, old);  // settled: the checksum is kept
  }
  const std::string before = RecordingSha256(dir);
  EXPECT_EQ(RecordingSha256(dir), before);
  {
    std::fstream imu(dir / "imu.csv", std::ios::in | std::ios::out | std::ios::binary);
    imu.seekp(5);
    imu << "9";  // "t_s\n9.01\n": the same size, other bytes
  }
  EXPECT_NE(RecordingSha256(dir), before);
  std::filesystem::remove_all(dir);
}

TEST(RecordingChecksum, NamesAMissingFile) {
  const auto dir = std::filesystem::temp_directory_path() / "adahrs_checksum_missing";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "meta.json") << "{}";
  try {
    RecordingSha256(dir);
    FAIL() << "accepted a run without imu.csv";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("imu.csv: cannot open"));
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace adahrs::calib
