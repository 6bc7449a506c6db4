// Bad input to the IMU calibration: a truncated or malformed recording, a wrong format version, a
// unit missing from a step, NaN or saturated samples, a design missing an orientation or rates —
// each refused or excluded with a message naming row and column (or step, unit and the reason).
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/imu_calibration/imu_reference_fit.h"
#include "calib/imu_calibration/imu_run_data.h"
#include "calib/solvers/linear_least_squares.h"
#include "common/gravity.h"
#include "hil/recording/recording_reader.h"
#include "tests/support/imu_recording_maker.h"

namespace adahrs::calib {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

const double kGLocal_mps2 = common::NormalGravityMps2(45.0, 0.0);

std::vector<std::string> ReadLines(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

void WriteLines(const fs::path& p, const std::vector<std::string>& lines) {
  std::ofstream out(p, std::ios::trunc);
  for (const std::string& l : lines) out << l << "\n";
}

std::vector<std::string> Cells(const std::string& line) {
  std::vector<std::string> cells(1);
  for (char c : line) {
    if (c == ',') {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  return cells;  // keeps empty cells, including trailing ones (v2 raw rows end in empty columns)
}

std::string Join(const std::vector<std::string>& cells) {
  std::string s;
  for (size_t i = 0; i < cells.size(); ++i) s += (i ? "," : "") + cells[i];
  return s;
}

// A short sensor-calibration run of two units, copied fresh for each test.
class ImuRunDataTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("adahrs_imu_run_data_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::vector<sensor_sim::ImuUnitParams> params = {
        sensor_sim::ImuUnitParams::Draw("IMU-0001", 1, sensor_sim::ModelProfile::kNominal),
        sensor_sim::ImuUnitParams::Draw("IMU-0002", 2, sensor_sim::ModelProfile::kNominal)};
    testing::ImuRecordingMaker maker(params, kGLocal_mps2, 3);
    maker.Run(Sequence(), dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  virtual calib::Sequence Sequence() {
    return testing::ShippedSequence("imu_sensor_calibration", 40);
  }
  std::string LoadError() {
    try {
      LoadImuRuns({dir_});
    } catch (const std::exception& e) {
      return e.what();
    }
    return "accepted";
  }
  fs::path dir_;
};

TEST_F(ImuRunDataTest, AUnitMissingFromAStepIsRefused) {
  // Step 4 is the accel step in orientation 12: drop IMU-0002's rows of it.
  std::vector<std::string> kept;
  for (const std::string& line : ReadLines(dir_ / "imu.csv")) {
    const auto c = Cells(line);
    if (c.size() > 3 && c[1] == "IMU-0002" && c[3] == "3") continue;
    kept.push_back(line);
  }
  WriteLines(dir_ / "imu.csv", kept);
  EXPECT_THAT(LoadError(), HasSubstr("unit IMU-0002 is missing from step 3 (accel, tag"));
}

TEST_F(ImuRunDataTest, TruncatedRecordingIsRefusedWithItsLine) {
  std::ofstream(dir_ / "imu.csv", std::ios::app) << "12.5,IMU-0001,7,3";
  const std::string message = LoadError();
  EXPECT_THAT(message, HasSubstr("imu.csv"));
  EXPECT_THAT(message, HasSubstr("line"));
}

TEST_F(ImuRunDataTest, WrongFormatVersionIsRefused) {
  nlohmann::json meta_file = nlohmann::json::parse(std::ifstream(dir_ / "meta.json"));
  meta_file["format_version"] = 99;
  std::ofstream(dir_ / "meta.json", std::ios::trunc) << meta_file.dump();
  EXPECT_THAT(LoadError(), HasSubstr("format_version"));
}

TEST_F(ImuRunDataTest, NanCellIsRefusedWithLineAndColumn) {
  auto lines = ReadLines(dir_ / "imu.csv");
  auto cells = Cells(lines[10]);
  cells[20] = "nan";  // gx
  lines[10] = Join(cells);
  WriteLines(dir_ / "imu.csv", lines);
  const std::string message = LoadError();
  EXPECT_THAT(message, HasSubstr("imu.csv:11: column 21 (gx)"));
}

TEST_F(ImuRunDataTest, SaturatedSamplesAreExcludedAndNamed) {
  auto lines = ReadLines(dir_ / "imu.csv");
  int changed = 0;
  size_t line_number = 0;
  for (size_t i = 1; i < lines.size() && changed < 1; ++i) {
    auto cells = Cells(lines[i]);
    if (cells[1] == "IMU-0001" && cells[4] != "0") {
      cells[8] = cells[9];  // az1_t1 = az1_t2: duty 1, the capture saturated
      lines[i] = Join(cells);
      line_number = i + 1;
      ++changed;
    }
  }
  WriteLines(dir_ / "imu.csv", lines);
  const ImuRunData data = LoadImuRuns({dir_});
  const ImuUnitData& unit = data.units.at("IMU-0001");
  ASSERT_EQ(unit.exclusions.size(), 1u);
  EXPECT_THAT(unit.exclusions[0],
              HasSubstr("imu.csv line " + std::to_string(line_number) + " column az1_t1"));
  EXPECT_THAT(unit.exclusions[0], HasSubstr("duty undefined"));
  EXPECT_TRUE(data.units.at("IMU-0002").exclusions.empty());
}

TEST_F(ImuRunDataTest, RowsInsideARejectedIntervalAreNotCalibrationData) {
  const hil::Recording rec = hil::ReadRecording(dir_);
  double t_first = -1.0;
  for (const auto& row : rec.imu) {
    if (row.step == 2 && row.tag != 0) {
      t_first = row.t_s;
      break;
    }
  }
  hil::RecordingMeta meta = rec.meta;
  meta.rejected_intervals = {{2, t_first, t_first + 0.095, "chamber excursion"}};
  std::ofstream(dir_ / "meta.json", std::ios::trunc) << meta.ToJson().dump();
  const ImuRunData data = LoadImuRuns({dir_});
  // 10 frames of both units lie inside the 95 ms interval (frames every 10 ms from t_first).
  EXPECT_EQ(data.units.at("IMU-0001").rejected_interval_rows, 10);
  EXPECT_EQ(data.units.at("IMU-0001").accel.front().samples.size(), 30u);
}

TEST_F(ImuRunDataTest, NoThermalRunIsRefusedWithTheReason) {
  const ImuRunData data = LoadImuRuns({dir_});
  try {
    FitImuReference(data.units.at("IMU-0001"), data.local_gravity_mps2);
    FAIL();
  } catch (const ImuInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("unit IMU-0001: no thermal_profile rows"));
  }
}

// A design without orientation 22: the six-position fit refuses it, naming the orientation.
class MissingOrientation : public ImuRunDataTest {
  calib::Sequence Sequence() override {
    calib::Sequence s = testing::ShippedSequence("imu_sensor_calibration", 40);
    s.steps.erase(s.steps.begin() + 5);  // accel 22
    // A thermal profile the F4 can run, so the fit reaches the six-position step.
    ThermalProfileStep profile{
        "T", {F4RampRate{-20.0, 5.0}, F4RampRate{60.0, 5.0}, F4RampRate{25.0, 5.0}, F4End{}}};
    s.steps.insert(s.steps.begin() + 2, Step{std::nullopt, profile});
    return s;
  }
};

TEST_F(MissingOrientation, IsRefusedNamingTheOrientation) {
  const ImuRunData data = LoadImuRuns({dir_});
  try {
    FitImuReference(data.units.at("IMU-0002"), data.local_gravity_mps2);
    FAIL();
  } catch (const DegenerateDesignError& e) {
    EXPECT_THAT(e.what(), HasSubstr("22"));
  }
}

}  // namespace
}  // namespace adahrs::calib
