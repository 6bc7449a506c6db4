#include "hil/recording/recording_reader.h"

#include <unistd.h>

#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hil/recording/recording_writer.h"

namespace adahrs::hil {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

class RecordingReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("adahrs_reader_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    RecordingWriter w(dir_, RecordingStorage::kPlainCsv);
    for (uint32_t i = 0; i < 3; ++i) {
      ImuRecordRow r;
      r.t_s = 0.01 * (i + 1);
      r.unit = "IMU-0001";
      r.seq = i;
      r.tag = 7;
      r.orientation = 21;
      r.chamber_c = -40.0;
      r.accel_ticks.fill(static_cast<uint16_t>(30000 + i));
      r.gyro_cnt = {4194304, -3, 8388607};
      r.temp_cnt = {1, 2, 65520};
      w.Append(r);
    }
    AdsRecordRow a;
    a.unit = "ADS-0001";
    a.ps_ref_pa = 69681.64;
    a.ps_cnt = -8388608;
    w.Append(a);
    w.WriteMetaJson({{"sample_rate_hz", 100}});
    w.Flush(true);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  void ReplaceInFile(const char* name, const std::string& from, const std::string& to) {
    const auto path = dir_ / name;
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find(from), from.size(), to);
    std::ofstream(path) << text;
  }

  std::string ErrorOf(const ReadOptions& options = {}) {
    try {
      ReadRecording(dir_, options);
    } catch (const RecordingError& e) {
      return e.what();
    }
    return "accepted";
  }

  std::filesystem::path dir_;
};

TEST_F(RecordingReaderTest, ReadsBackWhatTheWriterWrote) {
  const Recording rec = ReadRecording(dir_);
  ASSERT_EQ(rec.imu.size(), 3u);
  EXPECT_EQ(rec.imu[2].seq, 2u);
  EXPECT_EQ(rec.imu[2].accel_ticks[11], 30002);
  EXPECT_EQ(rec.imu[0].gyro_cnt[1], -3);
  EXPECT_EQ(rec.imu[0].temp_cnt[2], 65520);
  EXPECT_EQ(rec.imu[0].orientation, 21);
  EXPECT_DOUBLE_EQ(rec.imu[1].chamber_c, -40.0);
  ASSERT_EQ(rec.ads.size(), 1u);
  EXPECT_EQ(rec.ads[0].ps_cnt, -8388608);
  EXPECT_DOUBLE_EQ(rec.ads[0].ps_ref_pa, 69681.64);
  EXPECT_EQ(rec.meta.sample_rate_hz.value_or(0.0), 100.0);
}

TEST_F(RecordingReaderTest, StreamingHandsEachRowWithItsLineAndHoldsNone) {
  std::vector<std::pair<uint32_t, int>> imu;
  std::vector<int> ads_lines;
  const Recording rec = StreamRecording(
      dir_,
      {[&](ImuRecordRow&& r, int line) { imu.emplace_back(r.seq, line); },
       [&](AdsRecordRow&& r, int line) { ads_lines.push_back(r.ps_cnt == -8388608 ? line : -1); }});
  EXPECT_TRUE(rec.imu.empty());
  EXPECT_TRUE(rec.ads.empty());
  EXPECT_EQ(rec.meta.sample_rate_hz.value_or(0.0), 100.0);
  ASSERT_EQ(imu.size(), 3u);
  for (uint32_t i = 0; i < 3; ++i)
    EXPECT_EQ(imu[i], std::make_pair(i, static_cast<int>(i) + 2));  // line 1: header
  EXPECT_EQ(ads_lines, std::vector<int>{2});
  // An empty sink still checks its file's rows.
  ReplaceInFile("imu.csv", ",4194304,-3,", ",4194304,nan,");
  EXPECT_THROW(StreamRecording(dir_, {}), RecordingError);
}

TEST_F(RecordingReaderTest, BadCellNamesFileLineAndColumn) {
  ReplaceInFile("imu.csv", ",4194304,-3,", ",4194304,nan,");
  EXPECT_THAT(ErrorOf(),
              AllOf(HasSubstr("imu.csv:2"), HasSubstr("column 22 (gy)"), HasSubstr("'nan'")));
}

TEST_F(RecordingReaderTest, BadCellIsQuotedWithItsControlBytesEscaped) {
  ReplaceInFile("imu.csv", ",4194304,-3,", ",4194304,\x1b[2J\r,");
  const std::string error = ErrorOf();
  EXPECT_THAT(error, AllOf(HasSubstr("imu.csv:2"), HasSubstr("'\\x1B[2J\\r'")));
  EXPECT_EQ(error.find_first_of("\x1b\r"), std::string::npos) << error;
}

TEST_F(RecordingReaderTest, OutOfRangeTicksAreRefused) {
  ReplaceInFile("imu.csv", ",30001,", ",70000,");
  EXPECT_THAT(ErrorOf(),
              AllOf(HasSubstr("imu.csv:3"), HasSubstr("az1_t1"), HasSubstr("[0, 65535]")));
}

TEST_F(RecordingReaderTest, TruncatedTailIsReportedOrCountedOnRequest) {
  const auto path = dir_ / "imu.csv";
  std::ofstream(path, std::ios::app) << "0.04,IMU-0001,3,0,7";  // a crash mid-row
  EXPECT_THAT(ErrorOf(), AllOf(HasSubstr("imu.csv:5"), HasSubstr("truncated")));
  const Recording rec = ReadRecording(dir_, {.allow_truncated_tail = true});
  EXPECT_EQ(rec.imu.size(), 3u);
  EXPECT_EQ(rec.truncated_lines, 1);
}

TEST_F(RecordingReaderTest, WrongFormatVersionIsRefused) {
  ReplaceInFile("meta.json", "\"format_version\": 4", "\"format_version\": 5");
  EXPECT_THAT(ErrorOf(), AllOf(HasSubstr("meta.json"), HasSubstr("format_version is 5")));
}

// A version that would wrap to a readable one in 32 bits is refused as itself; a version that is
// not an integer is named as such, not called missing.
TEST_F(RecordingReaderTest, FormatVersionIsReadWideAndNamedByItsValue) {
  ReplaceInFile("meta.json", "\"format_version\": 4", "\"format_version\": 4294967299");
  EXPECT_THAT(ErrorOf(),
              HasSubstr("$.format_version is 4294967299; this software reads versions 1 to 4"));
  ReplaceInFile("meta.json", "\"format_version\": 4294967299", "\"format_version\": 3.0");
  EXPECT_THAT(ErrorOf(), HasSubstr("$.format_version is 3.0, not an integer"));
  ReplaceInFile("meta.json", "\"format_version\": 3.0", "\"format_version\": \"3\"");
  EXPECT_THAT(ErrorOf(), HasSubstr("$.format_version is \"3\", not an integer"));
}

// A unit's kind is one of the two the house knows, read as a kind, not kept as text.
TEST_F(RecordingReaderTest, UnknownUnitKindIsRefusedByItsPath) {
  nlohmann::json meta_file = nlohmann::json::parse(std::ifstream(dir_ / "meta.json"));
  meta_file["units"] = {{{"kind", "imu"}, {"serial", "IMU-0001"}},
                        {{"kind", "IMU"}, {"serial", "ADS-0001"}}};
  std::ofstream(dir_ / "meta.json") << meta_file.dump(2);
  EXPECT_THAT(ErrorOf(),
              AllOf(HasSubstr("meta.json"),
                    HasSubstr("$.units[1].kind: \"IMU\" is not \"imu\" or \"ads\"")));
  meta_file["units"][1]["kind"] = "ads";
  std::ofstream(dir_ / "meta.json") << meta_file.dump(2);
  const Recording rec = ReadRecording(dir_, {});
  ASSERT_EQ(rec.meta.units.size(), 2u);
  EXPECT_EQ(rec.meta.units[0].kind, common::UnitKind::kImu);
  EXPECT_EQ(rec.meta.units[1].kind, common::UnitKind::kAds);
}

// Per unit, rows come in arrival order; a copy, time going back, a unit meta.json does not list
// and a negative step are refused by file and line. Rows 2-4 of imu.csv are seq 0, 1, 2.
TEST_F(RecordingReaderTest, RowsOutOfArrivalOrderAreRefusedByLine) {
  const auto append = [&](const std::string& row) {
    std::ofstream(dir_ / "imu.csv", std::ios::app) << row;
  };
  std::ifstream in(dir_ / "imu.csv");
  std::string header, row1, row2, row3;
  std::getline(in, header);
  std::getline(in, row1);
  std::getline(in, row2);
  std::getline(in, row3);
  in.close();
  append(row3 + "\n");
  EXPECT_THAT(
      ErrorOf(),
      HasSubstr("imu.csv:5: unit IMU-0001 repeats its previous row (seq 2, t_s 0.030000 s)"));
  ReplaceInFile("imu.csv", row3 + "\n" + row3, row3 + "\n" + row1);
  EXPECT_THAT(ErrorOf(),
              HasSubstr("imu.csv:5: unit IMU-0001 t_s 0.010000 s goes back from 0.030000 s"));
  ReplaceInFile("imu.csv", row3 + "\n" + row1, row3);
  ASSERT_EQ(ErrorOf(), "accepted");
  ReplaceInFile("imu.csv", "0.0200,IMU-0001,1,0,", "0.0200,IMU-0001,1,-4,");
  EXPECT_THAT(ErrorOf(), HasSubstr("imu.csv:3: unit IMU-0001 step -4 is negative"));
  ReplaceInFile("imu.csv", "0.0200,IMU-0001,1,-4,", "0.0200,IMU-0001,1,0,");
  nlohmann::json meta_file = nlohmann::json::parse(std::ifstream(dir_ / "meta.json"));
  meta_file["units"] = {{{"kind", "imu"}, {"serial", "IMU-0002"}},
                        {{"kind", "ads"}, {"serial", "ADS-0001"}}};
  std::ofstream(dir_ / "meta.json") << meta_file.dump();
  EXPECT_THAT(ErrorOf(),
              HasSubstr("imu.csv:2: unit 'IMU-0001' is not listed in meta.json $.units"));
}

// Packets sharing an arrival time (a burst read at once) are not copies, even when their 8-bit
// counter comes round to the same value within the burst.
TEST_F(RecordingReaderTest, ABurstSharingOneTimeIsRead) {
  RecordingWriter w(dir_ / "burst");
  for (uint32_t i = 0; i < 300; ++i) {
    ImuRecordRow r;
    r.t_s = 1.0;
    r.unit = "IMU-0001";
    r.seq = i % 256;
    r.gyro_cnt = {static_cast<int32_t>(1000 + i % 7), static_cast<int32_t>(i), 5};
    w.Append(r);
  }
  w.WriteMetaJson({});
  w.Flush(true);
  EXPECT_EQ(ReadRecording(dir_ / "burst").imu.size(), 300u);
}

// A unit listed twice would have its rows counted twice by whoever walks the list.
TEST_F(RecordingReaderTest, UnitListedTwiceIsRefused) {
  nlohmann::json meta_file = nlohmann::json::parse(std::ifstream(dir_ / "meta.json"));
  meta_file["units"] = {{{"kind", "imu"}, {"serial", "IMU-0001"}},
                        {{"kind", "imu"}, {"serial", "IMU-0001"}}};
  std::ofstream(dir_ / "meta.json") << meta_file.dump();
  EXPECT_THAT(
      ErrorOf(),
      HasSubstr("meta.json: $.units[1].serial \"IMU-0001\" is listed already as $.units[0]"));
}

TEST_F(RecordingReaderTest, RawRowsHaveNoCompensatedValues) {
  const Recording rec = ReadRecording(dir_);
  EXPECT_EQ(rec.meta.format_version, 4);
  EXPECT_EQ(rec.imu[0].mode, 0);
  EXPECT_FALSE(rec.imu[0].comp.has_value());
  EXPECT_FALSE(rec.ads[0].alt_ft.has_value());
}

TEST_F(RecordingReaderTest, CompensatedRowReadsBackExactly) {
  {
    RecordingWriter w(dir_, RecordingStorage::kPlainCsv);
    ImuRecordRow r;
    r.t_s = 0.04;
    r.unit = "IMU-0001";
    r.seq = 3;
    r.mode = 3;
    r.comp = std::array<double, 9>{9.80665, -0.1, 0.2, 150.0, -3.5, 0.0, 1e-6, -2e-6, 0.0};
    r.comp_flags = 1;
    w.Append(r);
  }
  const Recording rec = ReadRecording(dir_);
  ASSERT_EQ(rec.imu.size(), 4u);
  ASSERT_TRUE(rec.imu[3].comp.has_value());
  EXPECT_EQ(rec.imu[3].mode, 3);
  EXPECT_EQ((*rec.imu[3].comp)[0], 9.80665);  // shortest round-trip text: exact
  EXPECT_EQ((*rec.imu[3].comp)[6], 1e-6);
  EXPECT_EQ(rec.imu[3].comp_flags, 1u);
}

TEST_F(RecordingReaderTest, CompensatedCellsMustMatchTheMode) {
  ReplaceInFile("imu.csv", ",65520,0,,,", ",65520,2,,,");
  EXPECT_THAT(ErrorOf(),
              AllOf(HasSubstr("imu.csv:2"), HasSubstr("(comp0)"), HasSubstr("mode is 2")));
}

TEST_F(RecordingReaderTest, RawModeWithAValueIsRefused) {
  ReplaceInFile("ads.csv", ",0,,,", ",0,12.5,,");
  EXPECT_THAT(ErrorOf(), AllOf(HasSubstr("ads.csv:2"), HasSubstr("(alt_ft)"), HasSubstr("raw")));
}

// A version-1 directory as the simulator wrote it before version 2 (literal text, the v1 header
// of docs/recording-format.md) is still read, without compensated values.
TEST_F(RecordingReaderTest, VersionOneRecordingIsStillRead) {
  std::filesystem::remove_all(dir_);
  std::filesystem::create_directories(dir_);
  std::ofstream(dir_ / "meta.json") << R"({"format_version": 1, "sample_rate_hz": 100})";
  std::ofstream(dir_ / "imu.csv")
      << kImuCsvHeaderV1 << "\n"
      << "0.0100,IMU-0001,7,3,4,21,25.000,0.0000,1,2,3,4,5,6,7,8,9,10,11,12,4194304,-5,6,7,8,9\n";
  std::ofstream(dir_ / "ads.csv")
      << kAdsCsvHeaderV1 << "\n"
      << "0.0100,ADS-0001,9,1,2,20.000,101325.00,0.00,-8388608,1,2,3,4\n";
  const Recording rec = ReadRecording(dir_);
  EXPECT_EQ(rec.meta.format_version, 1);
  ASSERT_EQ(rec.imu.size(), 1u);
  EXPECT_EQ(rec.imu[0].seq, 7u);
  EXPECT_EQ(rec.imu[0].accel_ticks[11], 12);
  EXPECT_EQ(rec.imu[0].temp_cnt[2], 9);
  EXPECT_EQ(rec.imu[0].mode, 0);
  EXPECT_FALSE(rec.imu[0].comp.has_value());
  ASSERT_EQ(rec.ads.size(), 1u);
  EXPECT_EQ(rec.ads[0].ps_cnt, -8388608);
  EXPECT_EQ(rec.ads[0].oat_cnt, 4);
}

TEST_F(RecordingReaderTest, VersionOneMetaWithALaterHeaderIsRefused) {
  ReplaceInFile("meta.json", "\"format_version\": 4", "\"format_version\": 1");
  EXPECT_THAT(ErrorOf(), AllOf(HasSubstr("imu.csv:1"), HasSubstr("version 1")));
}

// Version 2 has no frame column: the reader counts each unit's frames from seq and t_s as the
// writer does (frame_count.h), here across a 3 s gap (300 frames, the counter moved 44).
TEST_F(RecordingReaderTest, VersionTwoRowsGetTheirFramesCounted) {
  std::ofstream(dir_ / "meta.json") << R"({"format_version": 2})";
  std::ofstream(dir_ / "imu.csv") << kImuCsvHeaderV2 << "\n";
  std::ofstream(dir_ / "ads.csv")
      << kAdsCsvHeaderV2 << "\n"
      << "1.0000,ADS-0001,100,0,0,20.000,101325.00,0.00,1,1,2,3,4,0,,,\n"
      << "4.0000,ADS-0001,144,0,0,20.000,101325.00,0.00,2,1,2,3,4,0,,,\n";
  const Recording rec = ReadRecording(dir_);
  ASSERT_EQ(rec.ads.size(), 2u);
  EXPECT_EQ(rec.ads[0].frame, 100);  // 1.00 s: frame 100 has counter 100
  EXPECT_EQ(rec.ads[1].frame, 400);
}

// Versions 1 to 3 name the ADS raw counts ps_counts … oat_counts; they land in the same fields.
// A version-3 file with version 4's names says meta.json's version is wrong.
TEST_F(RecordingReaderTest, VersionThreeAdsCountColumnsAreReadByTheirOldNames) {
  std::ofstream(dir_ / "meta.json") << R"({"format_version": 3})";
  std::ofstream(dir_ / "imu.csv") << kImuCsvHeader << "\n";
  std::ofstream(dir_ / "ads.csv")
      << kAdsCsvHeaderV3 << "\n"
      << "1.0000,ADS-0001,100,0,0,20.000,101325.00,0.00,-8388608,1,2,3,4,0,,,,100,1.00\n";
  const Recording rec = ReadRecording(dir_);
  ASSERT_EQ(rec.ads.size(), 1u);
  EXPECT_EQ(rec.ads[0].ps_cnt, -8388608);
  EXPECT_EQ(rec.ads[0].pt_temp_cnt, 3);
  EXPECT_EQ(rec.ads[0].oat_cnt, 4);
  std::ofstream(dir_ / "ads.csv") << kAdsCsvHeader << "\n";
  EXPECT_THAT(ErrorOf(), AllOf(HasSubstr("ads.csv:1"), HasSubstr("'ps_counts' is missing")));
}

TEST_F(RecordingReaderTest, RejectedIntervalsAreReadAndApplied) {
  RecordingWriter w(dir_, RecordingStorage::kPlainCsv);
  w.WriteMetaJson(
      {{"rejected_intervals",
        {{{"step", 2}, {"t_start_s", 0.015}, {"t_end_s", 0.02}, {"reason", "interlock"}}}}});
  const Recording rec = ReadRecording(dir_);
  ASSERT_EQ(rec.meta.rejected_intervals.size(), 1u);
  EXPECT_EQ(rec.meta.rejected_intervals[0].step, 2);
  EXPECT_EQ(rec.meta.rejected_intervals[0].reason, "interlock");
  EXPECT_FALSE(IsRejected(rec, rec.imu[0].t_s));  // 0.01
  EXPECT_TRUE(IsRejected(rec, rec.imu[1].t_s));   // 0.02, the inclusive end
  EXPECT_FALSE(IsRejected(rec, rec.imu[2].t_s));  // 0.03
}

TEST_F(RecordingReaderTest, MalformedRejectedIntervalNamesItsPath) {
  // Planted in the file: the writer itself refuses such a meta (WriteMetaJson reads it first).
  const nlohmann::json meta_file = {
      {"format_version", kRecordingFormatVersion},
      {"rejected_intervals",
       {{{"step", 2}, {"t_start_s", 5.0}, {"t_end_s", 4.0}, {"reason", "x"}}}}};
  RecordingWriter w(dir_, RecordingStorage::kPlainCsv);
  EXPECT_THROW(w.WriteMetaJson(meta_file), RecordingError);
  std::ofstream(dir_ / "meta.json", std::ios::trunc) << meta_file.dump();
  EXPECT_THAT(ErrorOf(),
              AllOf(HasSubstr("$.rejected_intervals[0]"), HasSubstr("before t_start_s")));
}

TEST_F(RecordingReaderTest, MissingColumnIsRefusedByName) {
  ReplaceInFile("ads.csv", "ps_ref_pa", "ps_ref_hpa");
  EXPECT_THAT(ErrorOf(), AllOf(HasSubstr("ads.csv:1"), HasSubstr("column 'ps_ref_pa' is missing")));
}

TEST_F(RecordingReaderTest, RepeatedColumnNameIsRefused) {
  ReplaceInFile("ads.csv", "ps_ref_pa", "qc_ref_pa");
  EXPECT_THAT(ErrorOf(), AllOf(HasSubstr("ads.csv:1"), HasSubstr("'qc_ref_pa' repeats column")));
}

// A foreign logger's extra column, inserted in the middle of every line, is passed over and named;
// the format's columns are read by name, so every value read is the one written.
TEST_F(RecordingReaderTest, UnknownColumnIsIgnoredWithANote) {
  const Recording before = ReadRecording(dir_);
  const auto path = dir_ / "imu.csv";
  std::ifstream in(path);
  std::string line, text;
  for (int n = 0; std::getline(in, line); ++n) {
    const size_t third = line.find(',', line.find(',', line.find(',') + 1) + 1);
    text += line.substr(0, third + 1) + (n == 0 ? "humidity_pct" : std::to_string(40 + n)) +
            line.substr(third) + "\n";
  }
  in.close();
  std::ofstream(path) << text;
  const Recording after = ReadRecording(dir_);
  ASSERT_EQ(after.imu.size(), before.imu.size());
  for (size_t i = 0; i < after.imu.size(); ++i) {
    EXPECT_EQ(after.imu[i].seq, before.imu[i].seq);
    EXPECT_EQ(after.imu[i].step, before.imu[i].step);
    EXPECT_EQ(after.imu[i].accel_ticks, before.imu[i].accel_ticks);
    EXPECT_EQ(after.imu[i].gyro_cnt, before.imu[i].gyro_cnt);
    EXPECT_EQ(after.imu[i].temp_cnt, before.imu[i].temp_cnt);
  }
  ASSERT_EQ(after.notes.size(), 1u);
  EXPECT_THAT(
      after.notes[0],
      AllOf(HasSubstr("imu.csv"), HasSubstr("column 4 'humidity_pct'"), HasSubstr("ignored")));
  EXPECT_TRUE(before.notes.empty());
}

// Columns in another order than the writer's are found by name.
TEST_F(RecordingReaderTest, ColumnsAreFoundByNameInAnyOrder) {
  ReplaceInFile("ads.csv", "ps_ref_pa,qc_ref_pa", "qc_ref_pa,ps_ref_pa");
  const Recording rec = ReadRecording(dir_);
  ASSERT_EQ(rec.ads.size(), 1u);
  EXPECT_DOUBLE_EQ(rec.ads[0].qc_ref_pa,
                   69681.64);  // the file's values did not move: its names did
  EXPECT_DOUBLE_EQ(rec.ads[0].ps_ref_pa, 0.0);
}

}  // namespace
}  // namespace adahrs::hil
