// The reader's sample time check (hil/recording/sample_time_check.h) on recordings written here
// with known frames: a unit read in bursts within its line's buffering has no defect; phantom
// counter turns planted into one unit's frames are reported by unit, file and line, the unit
// beside it not; after a resume ($.resumed_t_s) a session's offsets are held to its first row's,
// so the whole turns the resumed clock cannot see pass while a turn slipped within it does not;
// a unit whose line meta.json does not state is not checked.
#include "hil/recording/sample_time_check.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>

#include "hil/recording/recording_reader.h"
#include "hil/recording/recording_writer.h"

namespace adahrs::hil {
namespace {

class SampleTimeCheckTest : public ::testing::Test {
 protected:
  std::filesystem::path dir_ = std::filesystem::temp_directory_path() /
                               ("adahrs_stc_" + std::to_string(::getpid()) + "_" +
                                ::testing::UnitTest::GetInstance()->current_test_info()->name());
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Frames [1000, 3000) of IMU-0001 and IMU-0002 read in bursts at the end of each second; the
  // frame `shift(serial, frame)` further on is written.
  void Write(const nlohmann::json& meta,
             const std::function<int64_t(const std::string&, int64_t)>& shift) {
    std::filesystem::remove_all(dir_);
    RecordingWriter writer(dir_, RecordingStorage::kPlainCsv);
    for (int64_t frame = 1000; frame < 3000; ++frame) {
      for (const char* serial : {"IMU-0001", "IMU-0002"}) {
        ImuRecordRow r;
        r.t_s = 0.01 * static_cast<double>((frame / 100 + 1) * 100);
        r.unit = serial;
        r.frame = frame + shift(serial, frame);
        r.seq = static_cast<uint32_t>(r.frame % 256);
        writer.Append(r);
      }
    }
    writer.Flush(true);
    nlohmann::json m = meta;
    m["format_version"] = kRecordingFormatVersion;
    std::ofstream(dir_ / kMetaJsonName) << m.dump();
  }
  static nlohmann::json Units(double buffering_s) {
    return {{"units",
             {{{"serial", "IMU-0001"}, {"line_buffering_s", buffering_s}},
              {{"serial", "IMU-0002"}, {"line_buffering_s", buffering_s}}}}};
  }
};

TEST_F(SampleTimeCheckTest, BurstsWithinTheBufferingPass) {
  Write(Units(1.2), [](const std::string&, int64_t) { return 0; });
  EXPECT_TRUE(ReadRecording(dir_).sample_time_defects.empty());
}

TEST_F(SampleTimeCheckTest, PlantedPhantomTurnsAreReportedByUnitAndLine) {
  // IMU-0002 one turn ahead from frame 1500 on (line 2 + 2 * 500 + 1 = 1003).
  Write(Units(1.2), [](const std::string& serial, int64_t frame) {
    return serial == "IMU-0002" && frame >= 1500 ? 256 : 0;
  });
  const std::vector<SampleTimeDefect> defects = ReadRecording(dir_).sample_time_defects;
  ASSERT_EQ(defects.size(), 1u);
  EXPECT_EQ(defects[0].unit, "IMU-0002");
  EXPECT_EQ(defects[0].first_line, 1003);
  EXPECT_EQ(defects[0].rows, 1500);
  EXPECT_NE(defects[0].Describe().find("imu.csv: unit IMU-0002: 1500 row(s)"), std::string::npos)
      << defects[0].Describe();
}

// A real line: the first row's count is right only modulo its counter turn's phase, here half a
// turn (1.28 s) off, so the offsets run from +0.28 to +1.27 s, beyond the 1.2 s bound taken from
// 0 but within it of the first row's; they pass, and a phantom turn after them is still found.
TEST_F(SampleTimeCheckTest, ARealLinesFirstRowSetsTheOffsetItsRowsAreHeldTo) {
  Write(Units(1.2), [](const std::string&, int64_t) { return 128; });
  EXPECT_TRUE(ReadRecording(dir_).sample_time_defects.empty());
  Write(Units(1.2), [](const std::string& serial, int64_t frame) {
    return 128 + (serial == "IMU-0001" && frame >= 2000 ? 256 : 0);
  });
  const std::vector<SampleTimeDefect> defects = ReadRecording(dir_).sample_time_defects;
  ASSERT_EQ(defects.size(), 1u);
  EXPECT_EQ(defects[0].unit, "IMU-0001");
  EXPECT_EQ(defects[0].first_line, 2 + 2 * 1000);
}

TEST_F(SampleTimeCheckTest, AResumedSessionIsHeldToItsFirstRow) {
  // From frame 2000 on, a resumed session: the clock continued from the last recorded time while
  // the units ran 7 s (700 frames) unheard, which the count of the first row after the resume
  // took up only modulo 256: every offset of the session 1.88 s further on.
  nlohmann::json meta = Units(1.2);
  meta["resumed_t_s"] = {20.5};
  Write(meta, [](const std::string&, int64_t frame) { return frame >= 2000 ? 188 : 0; });
  EXPECT_TRUE(ReadRecording(dir_).sample_time_defects.empty());
  Write(meta, [](const std::string& serial, int64_t frame) {
    return (frame >= 2000 ? 188 : 0) + (serial == "IMU-0001" && frame >= 2500 ? 256 : 0);
  });
  const std::vector<SampleTimeDefect> defects = ReadRecording(dir_).sample_time_defects;
  ASSERT_EQ(defects.size(), 1u);
  EXPECT_EQ(defects[0].unit, "IMU-0001");
  EXPECT_EQ(defects[0].first_line, 2 + 2 * 1500);
}

TEST_F(SampleTimeCheckTest, AUnitWhoseLineIsNotStatedIsNotChecked) {
  Write({{"units", {{{"serial", "IMU-0001"}}, {{"serial", "IMU-0002"}}}}},
        [](const std::string&, int64_t frame) { return frame >= 1500 ? 256 : 0; });
  EXPECT_TRUE(ReadRecording(dir_).sample_time_defects.empty());
}

}  // namespace
}  // namespace adahrs::hil
