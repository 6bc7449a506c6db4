// Run directories and constants files into records: fields taken from the files as written,
// checksums equal to those of independent tools (sha256sum), bad input refused by file and path.
#include "calib/records/records_sources.h"
#include "adahrs_build_paths.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include <functional>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/constants/constants_file.h"
#include "calib/records/unit_history_text.h"
#include "calib/sequence/sequence_json.h"
#include "hil/recording/recording_writer.h"
#include "tests/firmware_model/realistic_constants.h"

namespace adahrs::calib {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

class RecordsSourcesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("adahrs_rsrc_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_ / "run");
    const auto sequence = ParseSequenceFile(std::string(ADAHRS_SOURCE_DIR) +
                                            "/calib/sequences/imu_sensor_calibration.json");
    meta_ = {{"format_version", 4},
             {"run_id", "20240501-080000-cal"},
             {"started_utc", "2024-05-01T08:00:00Z"},
             {"status", "complete"},
             {"station", {{"name", "virtual lab"}}},
             {"sequence", SequenceToJson(sequence.sequence)},
             {"sequence_file", "calib/sequences/imu_sensor_calibration.json"},
             {"time_base", "pipeline clock seconds since the run started"},
             {"sample_rate_hz", 100},
             {"local_gravity_mps2", 9.80665},
             {"units",
              {{{"role", "imu1"},
                {"kind", "imu"},
                {"serial", "IMU-0001"},
                {"serial_number", 1},
                {"firmware", "1.0.0"},
                {"slot", 1},
                {"constants_version", 0},
                {"mode", 0}},
               {{"role", "imu2"},
                {"kind", "imu"},
                {"serial", "IMU-0002"},
                {"serial_number", 2},
                {"firmware", "1.0.0"},
                {"slot", 2},
                {"constants_version", 4},
                {"mode", 0}}}},
             {"instruments", nlohmann::json::array()},
             {"rejected_intervals",
              {{{"step", 2}, {"t_start_s", 10.0}, {"t_end_s", 12.5}, {"reason", "chamber"}},
               {{"step", 2}, {"t_start_s", 20.0}, {"t_end_s", 21.0}, {"reason", "lost"}}}}};
    WriteRun();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // meta.json and a recording of `rows` rows per unit, written by the recording writer; `edit`
  // may change a row before it is written.
  void WriteRun(const std::function<void(int, hil::ImuRecordRow&)>& edit = {}) {
    std::filesystem::remove(dir_ / "run" / "imu.csv");
    std::filesystem::remove(dir_ / "run" / "ads.csv");
    hil::RecordingWriter writer(dir_ / "run", hil::RecordingStorage::kPlainCsv);
    int n = 0;
    for (int i = 0; i < 5; ++i) {
      for (const char* serial : {"IMU-0001", "IMU-0002"}) {
        hil::ImuRecordRow r;
        r.t_s = 0.01 * i;
        r.unit = serial;
        r.seq = static_cast<uint32_t>(i);
        r.orientation = 31;
        if (edit) edit(n, r);
        ++n;
        writer.Append(r);
      }
    }
    writer.Flush(true);
    std::ofstream(dir_ / "run" / "meta.json") << meta_.dump(2);
  }

  // sha256sum of `files` concatenated: the independent checksum.
  std::string Sha256sum(const std::string& files) {
    const std::string command = "cat " + files + " | sha256sum";
    FILE* pipe = ::popen(command.c_str(), "r");
    char buffer[128] = {};
    EXPECT_NE(std::fgets(buffer, sizeof buffer, pipe), nullptr);
    ::pclose(pipe);
    return std::string(buffer).substr(0, 64);
  }

  std::string ErrorOf() {
    try {
      RunRecordFromDirectory(dir_ / "run");
    } catch (const std::exception& e) {
      return e.what();
    }
    return "accepted";
  }

  std::filesystem::path dir_;
  nlohmann::json meta_;
};

TEST_F(RecordsSourcesTest, RunRecordCarriesMetaStepsUnitsAndTheRecordingChecksum) {
  const RunRecord run = RunRecordFromDirectory(dir_ / "run");
  EXPECT_EQ(run.run_id, "20240501-080000-cal");
  EXPECT_EQ(run.status, "complete");
  EXPECT_EQ(run.station_name, "virtual lab");
  EXPECT_EQ(run.sequence_name, "imu_sensor_calibration");
  // The shipped sequence: 12 steps, no explicit TAGs, so TAGs 1..12 in step order (sequence.h).
  ASSERT_EQ(run.steps.size(), 12u);
  EXPECT_EQ(run.steps[0].kind, "prompt");
  EXPECT_EQ(run.steps[2].kind, "accel");
  EXPECT_EQ(run.steps[11].tag, 12);
  EXPECT_DOUBLE_EQ(run.steps[2].rejected_s, 3.5);  // 2.5 s + 1.0 s
  ASSERT_EQ(run.units.size(), 2u);
  EXPECT_EQ(run.units[1].serial, "IMU-0002");
  EXPECT_EQ(run.units[1].constants_version, 4);
  const std::string d = (dir_ / "run").string();
  EXPECT_EQ(run.recording_sha256, Sha256sum(d + "/meta.json " + d + "/imu.csv " + d + "/ads.csv"));
}

// add-run reads the rows before recording a run: what the pipeline would not trust is refused
// by file and line.
TEST_F(RecordsSourcesTest, RowsTheFitWouldNotTrustAreRefusedByLine) {
  WriteRun([](int n, hil::ImuRecordRow& r) {
    if (n == 6) r.unit = "IMU-0009";
  });
  EXPECT_THAT(ErrorOf(), AllOf(HasSubstr("imu.csv:8"), HasSubstr("'IMU-0009' is not listed")));
  WriteRun([](int n, hil::ImuRecordRow& r) {
    if (n == 7) r.t_s = 0.0;
  });
  EXPECT_THAT(ErrorOf(),
              AllOf(HasSubstr("imu.csv:9"), HasSubstr("IMU-0002 t_s 0.000000 s goes back")));
  WriteRun([](int n, hil::ImuRecordRow& r) {
    if (n == 5) {
      r.t_s = 0.01;
      r.seq = 1;
    }
  });
  EXPECT_THAT(ErrorOf(),
              AllOf(HasSubstr("imu.csv:7"), HasSubstr("IMU-0002 repeats its previous row")));
  WriteRun();
  { std::ofstream(dir_ / "run" / "imu.csv", std::ios::app) << "0.05,IMU-0001,5,0,0,31,x"; }
  EXPECT_THAT(ErrorOf(), HasSubstr("imu.csv:12"));  // a torn last line, in a complete run
  meta_["status"] = "interrupted";
  std::ofstream(dir_ / "run" / "meta.json") << meta_.dump(2);
  EXPECT_EQ(ErrorOf(), "accepted");  // the crash that interrupted it tore the line
}

TEST_F(RecordsSourcesTest, BadMetaIsRefusedWithFileAndPath) {
  meta_["format_version"] = 1;
  WriteRun();
  EXPECT_THAT(ErrorOf(), HasSubstr("meta.json"));
  EXPECT_THAT(ErrorOf(), HasSubstr("$.format_version"));
  meta_["format_version"] = 4;
  meta_["rejected_intervals"][1]["step"] = 40;
  WriteRun();
  EXPECT_THAT(ErrorOf(), HasSubstr("$.rejected_intervals[1].step"));
  meta_["rejected_intervals"][1]["step"] = 2;
  meta_["units"][0].erase("serial");
  WriteRun();
  EXPECT_THAT(ErrorOf(), HasSubstr("$.units[0].serial"));
}

TEST_F(RecordsSourcesTest, ConstantsFilesBecomeVersionsAndTheHistoryShowsThem) {
  ConstantsFile file;
  file.serial = "IMU-0001";
  file.kind = hil::UnitKind::kImu;
  file.strategy = "reference";
  file.created_utc = "2024-05-01T09:00:00Z";
  file.software_version = "0.1.0";
  file.imu = firmware_model::testing::RealisticImu(7);
  firmware_model::ImuCalibrationConstants se = *file.imu;  // 0.1 % of each value
  for (auto& t : se.thermal) {
    for (double& k : t.k) k = 1e-3 * std::abs(k);
  }
  for (auto& a : se.accel)
    a = {1e-3 * std::abs(a.offset_duty), 1e-3 * std::abs(a.scale_duty_per_g)};
  for (auto& g : se.gyro) {
    g.null_cnt = 1.0;
    for (double& l : g.l) l = 1e-3 * std::abs(l);
  }
  for (auto& row : se.ca_mps2_per_g) {
    for (double& v : row) v = 1e-3 * std::abs(v);
  }
  for (auto& row : se.cg) {
    for (double& v : row) v = 1e-3 * std::abs(v);
  }
  file.standard_errors = ImuStandardErrorsJson(se);
  file.provenance.recordings = {{"runs/cal1", std::string(64, 'a')}};
  file.provenance.sequence_names = {"imu_sensor_calibration"};
  const auto first = dir_ / "first.json";
  WriteConstantsFile(first, file);
  file.strategy = "joint";
  const auto second = dir_ / "second.json";
  WriteConstantsFile(second, file);

  const ConstantsRecord record = ConstantsRecordFromFile(first);
  EXPECT_EQ(record.serial, "IMU-0001");
  EXPECT_EQ(record.kind, "imu");
  EXPECT_EQ(record.file_sha256, Sha256sum(first.string()));
  EXPECT_THAT(record.provenance_json, HasSubstr("runs/cal1"));

  RecordsStore store(dir_ / "records.sqlite");
  store.AddRun(RunRecordFromDirectory(dir_ / "run"));
  EXPECT_EQ(store.AddConstants(record), 1);
  EXPECT_EQ(store.AddConstants(ConstantsRecordFromFile(second)), 2);
  const std::string text = FormatUnitHistory(store.History("IMU-0001"));
  EXPECT_THAT(text, HasSubstr("IMU-0001 (imu)"));
  EXPECT_THAT(text, HasSubstr("runs: 1"));
  EXPECT_THAT(text, HasSubstr("imu_sensor_calibration"));
  EXPECT_THAT(text, HasSubstr("constants versions: 2"));
  EXPECT_THAT(text, HasSubstr("v2  2024-05-01T09:00:00Z  strategy joint"));
  EXPECT_THAT(text, HasSubstr("not downloaded"));
}

}  // namespace
// A recording whose line states its buffering: rows whose sample time left it (a phantom counter
// turn planted in one unit's frames) are refused by unit and line, unless accepted explicitly.
TEST_F(RecordsSourcesTest, SampleTimeDefectsAreRefusedUnlessAccepted) {
  for (auto& unit : meta_["units"]) unit["line_buffering_s"] = 1.2;
  WriteRun([](int n, hil::ImuRecordRow& r) { r.frame = n / 2; });
  EXPECT_EQ(ErrorOf(), "accepted");
  WriteRun([](int n, hil::ImuRecordRow& r) { r.frame = n / 2 + (n >= 7 && n % 2 == 1 ? 256 : 0); });
  EXPECT_THAT(ErrorOf(),
              AllOf(HasSubstr("sample time defects"),
                    HasSubstr("imu.csv: unit IMU-0002: 2 row(s)"),
                    HasSubstr("the first at line 9 (+2.560 s)")));
  RunRecordOptions accept;
  accept.accept_sample_time_defects = true;
  EXPECT_EQ(RunRecordFromDirectory(dir_ / "run", accept).units.size(), 2u);
}

}  // namespace adahrs::calib
