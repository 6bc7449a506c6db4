// CsvFileWriter's compressed files, read back by zlib (an independent reader): the members the
// compressing thread writes while rows are still appended come back as the text in order, Flush
// leaves every member on disk, and a failed write on that thread (a full disk) is thrown by the
// appending thread's next call, naming the file.
#include "hil/recording/csv_file_writer.h"

#include <unistd.h>
#include <zlib.h>

#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace adahrs::hil {
namespace {

using ::testing::HasSubstr;

std::string Gunzip(const std::filesystem::path& path) {
  gzFile in = gzopen(path.c_str(), "rb");
  if (in == nullptr) return "<cannot open>";
  std::string text;
  char chunk[65536];
  int n = 0;
  while ((n = gzread(in, chunk, sizeof chunk)) > 0) text.append(chunk, static_cast<size_t>(n));
  gzclose(in);
  return n < 0 ? "<gzread error>" : text;
}

class CsvFileWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("adahrs_csvfile_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(CsvFileWriterTest, MembersWrittenWhileRowsAreAppendedComeBackInOrder) {
  const std::filesystem::path path = dir_ / "imu.csv.gz";
  std::string expected;
  {
    CsvFileWriter file(path);
    // 60 MB of rows: about 240 members ended by FlushIfDue and some by a full buffer, each
    // compressed while the next fills.
    for (int i = 0; i < 600000; ++i) {
      const std::string row = std::to_string(i) + ",IMU-0001," + std::to_string(i % 256) +
                              std::string(static_cast<size_t>(60 + i % 37), 'x') + "\n";
      file.Append(row);
      expected += row;
      if (i % 1000 == 999) file.FlushIfDue();
    }
    file.Flush();
    // Flush returned: everything is on disk before the writer is destroyed.
    EXPECT_EQ(Gunzip(path), expected);
    file.Append("last\n");
  }
  EXPECT_EQ(Gunzip(path), expected + "last\n");
}

TEST_F(CsvFileWriterTest, AFailedWriteOnTheCompressingThreadIsThrownNamingTheFile) {
  const std::filesystem::path path = dir_ / "imu.csv.gz";
  std::filesystem::create_symlink("/dev/full", path);
  CsvFileWriter file(path);
  const std::string row(200, 'x');
  try {
    for (int i = 0; i < 100000; ++i) {
      file.Append(row + "\n");
      file.FlushIfDue();
    }
    file.Flush();
    FAIL() << "writes to /dev/full succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string()));
    EXPECT_THAT(e.what(), HasSubstr("write failed"));
  }
}

TEST_F(CsvFileWriterTest, APlainFileOnAFullDiskFailsAtItsFlush) {
  const std::filesystem::path path = dir_ / "imu.csv";
  std::filesystem::create_symlink("/dev/full", path);
  CsvFileWriter file(path);
  file.Append("row\n");
  try {
    file.Flush();
    FAIL() << "a write to /dev/full succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string() + ": write failed"));
  }
}

}  // namespace
}  // namespace adahrs::hil
