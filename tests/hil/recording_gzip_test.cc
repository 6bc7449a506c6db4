// Compressed recordings (imu.csv.gz, ads.csv.gz): written by RecordingWriter as gzip members that
// end at flushes, read back by the project's reader and by Python's gzip module (an independent
// client, as pandas and numpy use it); a file cut inside its last member (a crash) reads up to the
// cut and says so, and is cut back to the last complete member so a resumed run appends after it.
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hil/recording/recording_reader.h"
#include "hil/recording/recording_writer.h"
#include "hil/recording/torn_tail.h"

namespace adahrs::hil {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

ImuRecordRow Row(int i) {
  ImuRecordRow r;
  r.t_s = 0.01 * i;
  r.unit = "IMU-0001";
  r.seq = static_cast<uint32_t>(i % 256);
  r.accel_ticks.fill(static_cast<uint16_t>(20000 + i % 5000));
  r.gyro_cnt = {4194304 + i, -i, 7};
  return r;
}

class RecordingGzipTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("adahrs_gzip_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Rows [first, first + count) in members of `per_member` rows: Flush ends each member.
  void Write(int first, int count, int per_member) {
    RecordingWriter w(dir_);
    w.WriteMetaJson({{"units", {{{"kind", "imu"}, {"serial", "IMU-0001"}}}}});
    for (int i = first; i < first + count; ++i) {
      w.Append(Row(i));
      if ((i - first + 1) % per_member == 0) w.Flush(false);
    }
    w.Flush(true);
  }

  std::filesystem::path dir_;
};

TEST_F(RecordingGzipTest, RowsComeBackFromEveryMember) {
  Write(0, 1000, 300);  // members of 300, 300, 300, 100 rows
  EXPECT_TRUE(std::filesystem::exists(dir_ / "imu.csv.gz"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "imu.csv"));
  const Recording rec = ReadRecording(dir_);
  ASSERT_EQ(rec.imu.size(), 1000u);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(rec.imu[i].gyro_cnt[0], 4194304 + i) << i;
  EXPECT_EQ(rec.truncated_lines, 0);
}

// Python's gzip module (what pandas.read_csv uses for .gz) reads every member: the header once
// and one line per row, the same text the plain writer writes.
TEST_F(RecordingGzipTest, PythonsGzipReadsTheMembersAsThePlainText) {
  Write(0, 1000, 300);
  const std::filesystem::path plain = dir_ / "plain";
  {
    RecordingWriter w(plain, RecordingStorage::kPlainCsv);
    for (int i = 0; i < 1000; ++i) w.Append(Row(i));
    w.Flush(true);
  }
  const std::filesystem::path out = dir_ / "python.csv";
  const std::string command =
      "/usr/bin/python3 -c \"import gzip,sys; "
      "open(sys.argv[2],'wb').write(gzip.open(sys.argv[1]).read())\" " +
      (dir_ / "imu.csv.gz").string() + " " + out.string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  EXPECT_EQ(ReadAll(out), ReadAll(plain / "imu.csv"));
}

// A crash mid-member: every cut inside the last member reads back as the rows before it (a
// prefix of what was written) and one truncated line, refused unless allowed.
TEST_F(RecordingGzipTest, AFileCutInsideItsLastMemberReadsUpToTheCut) {
  Write(0, 600, 300);
  const std::filesystem::path gz = dir_ / "imu.csv.gz";
  const std::string whole = ReadAll(gz);
  Write(600, 300, 300);  // a third member, then cut
  const std::string longer = ReadAll(gz);
  for (size_t cut = whole.size() + 1; cut < longer.size(); cut += 97) {
    std::ofstream(gz, std::ios::binary | std::ios::trunc) << longer.substr(0, cut);
    const Recording rec = ReadRecording(dir_, {.allow_truncated_tail = true});
    ASSERT_GE(rec.imu.size(), 600u) << cut;
    for (size_t i = 0; i < rec.imu.size(); ++i) {
      ASSERT_EQ(rec.imu[i].gyro_cnt[0], 4194304 + static_cast<int>(i)) << cut;
    }
    EXPECT_EQ(rec.truncated_lines, 1) << cut;
    try {
      ReadRecording(dir_);
      ADD_FAILURE() << "accepted a cut member at " << cut;
    } catch (const RecordingError& e) {
      EXPECT_THAT(e.what(), AllOf(HasSubstr("imu.csv.gz:"), HasSubstr("truncated")));
    }
  }
}

// Resume: the torn member is set aside, the file ends at its last complete member again, and
// rows appended after it read back with the ones before the crash.
TEST_F(RecordingGzipTest, ATornMemberIsSetAsideAndTheRunAppendsAfterTheLastComplete) {
  Write(0, 600, 300);
  const std::filesystem::path gz = dir_ / "imu.csv.gz";
  const std::string complete = ReadAll(gz);
  Write(600, 300, 300);
  const std::string longer = ReadAll(gz);
  const size_t cut = complete.size() + (longer.size() - complete.size()) / 2;
  std::ofstream(gz, std::ios::binary | std::ios::trunc) << longer.substr(0, cut);

  const auto torn = SetAsideTornTail(gz);
  ASSERT_TRUE(torn.has_value());
  EXPECT_EQ(torn->filename(), "imu.csv.gz.torn-1");
  EXPECT_EQ(ReadAll(*torn), longer.substr(complete.size(), cut - complete.size()));
  EXPECT_EQ(ReadAll(gz), complete);
  EXPECT_FALSE(SetAsideTornTail(gz).has_value());  // a clean end stays as it is

  Write(1000, 10, 300);
  const Recording rec = ReadRecording(dir_);
  ASSERT_EQ(rec.imu.size(), 610u);
  EXPECT_EQ(rec.imu[599].gyro_cnt[0], 4194304 + 599);
  EXPECT_EQ(rec.imu[600].gyro_cnt[0], 4194304 + 1000);
}

TEST_F(RecordingGzipTest, BytesAfterACompleteMemberThatAreNotGzipAreRefused) {
  Write(0, 10, 300);
  std::ofstream(dir_ / "imu.csv.gz", std::ios::binary | std::ios::app) << "0.5,IMU-0001\n";
  try {
    ReadRecording(dir_, {.allow_truncated_tail = true});
    FAIL() << "read past foreign bytes";
  } catch (const RecordingError& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("imu.csv.gz"), HasSubstr("corrupt gzip data")));
  }
}

TEST_F(RecordingGzipTest, BothFormsOfAFileAreRefusedByName) {
  Write(0, 10, 300);
  std::ofstream(dir_ / "imu.csv") << kImuCsvHeader << "\n";
  try {
    ReadRecording(dir_);
    FAIL() << "read a directory holding imu.csv and imu.csv.gz";
  } catch (const RecordingError& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("imu.csv and "), HasSubstr("imu.csv.gz both exist")));
  }
  EXPECT_THROW(RecordingWriter w(dir_), std::runtime_error);
}

// A run keeps the form it started with: a writer asked for gzip appends to an existing plain file.
TEST_F(RecordingGzipTest, AResumedRunKeepsItsForm) {
  {
    RecordingWriter w(dir_, RecordingStorage::kPlainCsv);
    w.WriteMetaJson({});
    w.Append(Row(1));
    w.Flush(true);
  }
  {
    RecordingWriter w(dir_, RecordingStorage::kGzip);
    w.Append(Row(2));
    w.Flush(true);
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ / "imu.csv.gz"));
  EXPECT_EQ(ReadRecording(dir_).imu.size(), 2u);
}

}  // namespace
}  // namespace adahrs::hil
