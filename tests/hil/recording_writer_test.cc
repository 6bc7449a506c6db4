#include "hil/recording/recording_writer.h"
#include "adahrs_build_paths.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace adahrs::hil {
namespace {

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::filesystem::path FreshDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("adahrs_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir;
}

// The header the code writes must be the one the contract documents (docs/recording-format.md),
// so the two cannot drift apart.
TEST(RecordingWriter, HeadersMatchTheDocumentedContract) {
  const std::string doc =
      ReadAll(std::filesystem::path(ADAHRS_SOURCE_DIR) / "docs/recording-format.md");
  for (std::string_view header : {kImuCsvHeader,
                                  kAdsCsvHeader,
                                  kImuCsvHeaderV2,
                                  kAdsCsvHeaderV2,
                                  kImuCsvHeaderV1,
                                  kAdsCsvHeaderV1}) {
    std::string quoted(1, '`');
    quoted.append(header).push_back('`');
    EXPECT_NE(doc.find(quoted), std::string::npos) << header;
  }
}

TEST(RecordingWriter, WritesRowsWithEveryColumnAndAppendsAcrossReopen) {
  const auto dir = FreshDir("rec");
  {
    RecordingWriter w(dir, RecordingStorage::kPlainCsv);
    ImuRecordRow row;
    row.t_s = 1.25;
    row.unit = "IMU-0001";
    row.seq = 65535;
    row.step = 2;
    row.tag = 200;
    row.orientation = 31;
    row.chamber_c = -20.5;
    row.table_rate_dps = 150.0;
    for (int i = 0; i < 12; ++i) row.accel_ticks[i] = static_cast<uint16_t>(29000 + i);
    row.gyro_cnt = {4194304, -1, 7340032};
    row.temp_cnt = {40000, 41000, 42000};
    w.Append(row);
    w.WriteMetaJson({{"sample_rate_hz", 100}});
    w.Flush(true);
  }
  {
    RecordingWriter w(
        dir, RecordingStorage::kPlainCsv);  // a resumed run appends, without a second header
    AdsRecordRow row;
    row.unit = "ADS-0001";
    row.ps_cnt = -8388608;
    w.Append(row);
    w.Flush(true);
  }
  const std::string imu = ReadAll(dir / "imu.csv");
  EXPECT_EQ(imu,
            std::string(kImuCsvHeader) + "\n" +
                "1.2500,IMU-0001,65535,2,200,31,-20.500,150.0000,29000,29001,29002,29003,29004,"
                "29005,29006,29007,29008,29009,29010,29011,4194304,-1,7340032,40000,41000,42000,"
                "0,,,,,,,,,,,255,2.55\n");  // frame: the one nearest 1.25 s that is seq mod 256
  const std::string ads = ReadAll(dir / "ads.csv");
  EXPECT_EQ(std::count(ads.begin(), ads.end(), '\n'), 2);
  EXPECT_NE(ads.find(",-8388608,"), std::string::npos);
  const auto meta = nlohmann::json::parse(ReadAll(dir / "meta.json"));
  EXPECT_EQ(meta.at("format_version"), kRecordingFormatVersion);
  std::filesystem::remove_all(dir);
}

// Compensated values are written in the shortest text that reads back to the same double, so a
// value of the Q31 grid (here 2^-27 g, the mode-2 accel LSB) survives the CSV exactly.
TEST(RecordingWriter, CompensatedCellsFollowTheMode) {
  const auto dir = FreshDir("rec_comp");
  {
    RecordingWriter w(dir, RecordingStorage::kPlainCsv);
    ImuRecordRow row;
    row.unit = "IMU-0002";
    row.mode = 2;
    row.comp = std::array<double, 9>{1.0, -0.5, std::ldexp(1.0, -27), 0, 0, 0, 150.0, -150.0, 0.25};
    row.comp_flags = 2;
    w.Append(row);
    AdsRecordRow ads;
    ads.unit = "ADS-0001";
    ads.mode = 1;
    ads.alt_ft = 35000.5;
    ads.cas_kt = 250.125;
    w.Append(ads);
    w.Flush(false);
  }
  const std::string imu = ReadAll(dir / "imu.csv");
  EXPECT_NE(imu.find(",2,1,-0.5,7.450580596923828e-09,0,0,0,150,-150,0.25,2,"), std::string::npos)
      << imu;
  const std::string ads = ReadAll(dir / "ads.csv");
  EXPECT_NE(ads.find(",1,35000.5,250.125,0,"), std::string::npos) << ads;
  std::filesystem::remove_all(dir);
}

TEST(RecordingWriter, RefusesToAppendToAnotherVersionsFile) {
  const auto dir = FreshDir("rec_v1");
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "imu.csv") << kImuCsvHeaderV1 << "\n";
  try {
    RecordingWriter w(dir, RecordingStorage::kPlainCsv);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("imu.csv:1: cannot append"), std::string::npos)
        << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(RecordingWriter, UnwritableDirectoryNamesThePath) {
  try {
    RecordingWriter w("/proc/adahrs_no_such_dir/run");
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("/proc/adahrs_no_such_dir"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace adahrs::hil
