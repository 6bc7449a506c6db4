// The frame and t_sample_s columns (recording format version 3): the writer counts each unit's
// frame from its counter and arrival times, the reader gives it back; a gap longer than a counter
// turn (> 2.56 s) and a writer reopened on the file (a resumed run) keep the true frame index,
// never short by a multiple of 256. Truth: the frames the rows were made from.
#include <unistd.h>

#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hil/recording/recording_reader.h"
#include "hil/recording/recording_writer.h"

namespace adahrs::hil {
namespace {

using ::testing::HasSubstr;

class RecordingFrameTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("adahrs_frame_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Rows of two units for the true frames [from, to), arriving in bursts of 50 frames; the
  // writer is given no frame.
  void Write(int64_t from, int64_t to, RecordingStorage storage) {
    RecordingWriter w(dir_, storage);
    w.WriteMetaJson({});
    for (int64_t f = from; f < to; ++f) {
      for (const char* unit : {"IMU-0001", "IMU-0002"}) {
        ImuRecordRow r;
        r.unit = unit;
        r.t_s = 0.01 * static_cast<double>((f / 50 + 1) * 50);
        r.seq = static_cast<uint32_t>(f % 256);
        r.gyro_cnt[0] = static_cast<int32_t>(f);  // the truth, carried through the file
        w.Append(r);
      }
    }
    w.Flush(true);
  }

  std::filesystem::path dir_;
};

TEST_F(RecordingFrameTest, ALongGapAndAReopenedWriterKeepTheTrueFrame) {
  for (RecordingStorage storage : {RecordingStorage::kGzip, RecordingStorage::kPlainCsv}) {
    std::filesystem::remove_all(dir_);
    Write(300, 800, storage);
    Write(1170, 1500, storage);  // reopened after a 3.7 s gap: 370 frames, 114 mod 256
    Write(1756, 1900, storage);  // reopened after exactly one turn: the counter looks unchanged
    const Recording rec = ReadRecording(dir_);
    ASSERT_EQ(rec.imu.size(), 2u * (500 + 330 + 144));
    for (const ImuRecordRow& r : rec.imu) {
      EXPECT_EQ(r.frame, r.gyro_cnt[0]) << r.unit << " t_s " << r.t_s;
    }
  }
}

TEST_F(RecordingFrameTest, AFrameGoingBackOrOffItsCounterIsRefusedByLine) {
  Write(300, 310, RecordingStorage::kPlainCsv);
  const std::filesystem::path csv = dir_ / "imu.csv";
  std::string text;
  {
    std::ifstream in(csv);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  // Line 4 is IMU-0001's second row (frame 301, 3.01 s).
  const auto edit = [&](const std::string& from, const std::string& to) {
    std::string edited = text;
    edited.replace(edited.find(from), from.size(), to);
    std::ofstream(csv) << edited;
    try {
      ReadRecording(dir_);
    } catch (const RecordingError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(edit(",301,3.01\n", ",45,0.45\n"),
              HasSubstr("imu.csv:4: unit IMU-0001 frame 45 goes back from 300"));
  EXPECT_THAT(edit(",301,3.01\n", ",302,3.02\n"),
              HasSubstr("imu.csv:4: unit IMU-0001 frame 302 is not its seq 45 modulo 256"));
  EXPECT_THAT(edit(",301,3.01\n", ",301,3.11\n"), HasSubstr("imu.csv:4: column 39 (t_sample_s)"));
}

}  // namespace
}  // namespace adahrs::hil
