#include "calib/records/records_store.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/records/download_records.h"
#include "calib/records/records_schema.h"
#include "tests/support/python_sqlite.h"

namespace adahrs::calib {
namespace {

using ::testing::HasSubstr;

class RecordsStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("adahrs_records_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    db_ = dir_ / "records.sqlite";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Reads the database with Python's own sqlite3 module: an independent reader of what we wrote.
  std::string PythonQuery(const std::string& sql) {
    const auto [out, status] = adahrs::testing::PythonSqlite(db_, sql, dir_);
    EXPECT_EQ(status, 0) << sql << ": " << out;
    return out;
  }

  static RunRecord Run(const std::string& run_id, const std::string& sha) {
    RunRecord run;
    run.run_id = run_id;
    run.run_dir = "/runs/" + run_id;
    run.sequence_name = "imu_sensor_calibration";
    run.sequence_file = "calib/sequences/imu_sensor_calibration.json";
    run.station_name = "virtual lab";
    run.started_utc = "2024-05-01T08:00:00Z";
    run.status = "complete";
    run.recording_sha256 = sha;
    run.meta_json = "{}";
    run.units = {{"IMU-0001", "imu", "imu1", 1, "1.0.0", std::nullopt, 0},
                 {"IMU-0002", "imu", "imu2", 2, "1.0.0", int64_t{3}, 0}};
    run.steps = {{0, "prompt", 1, 0.0}, {1, "accel", 2, 1.5}};
    return run;
  }

  static ConstantsRecord Constants(const std::string& serial, const std::string& sha) {
    return {serial,
            "imu",
            "reference",
            "2024-05-01T09:00:00Z",
            "0.1.0",
            sha,
            "{\"serial\": \"" + serial + "\"}",
            "{\"recordings\": []}"};
  }

  std::filesystem::path dir_;
  std::filesystem::path db_;
};

TEST_F(RecordsStoreTest, NewDatabaseIsAtTheCurrentSchemaVersionInWalMode) {
  { RecordsStore store(db_); }
  EXPECT_EQ(PythonQuery("SELECT version FROM schema_version"), "[(3,)]\n");
  EXPECT_EQ(PythonQuery("PRAGMA journal_mode"), "[('wal',)]\n");
  EXPECT_EQ(PythonQuery("SELECT name FROM sqlite_master WHERE type = 'table' ORDER BY name"),
            "[('acceptance_attempts',), ('acceptance_results',), ('constants',), ('downloads',), "
            "('run_units',), "
            "('runs',), ('schema_version',), ('steps',), ('units',)]\n");
  // Reopening an up-to-date database changes nothing.
  { RecordsStore again(db_); }
  EXPECT_EQ(PythonQuery("SELECT count(*) FROM schema_version"), "[(1,)]\n");
}

TEST_F(RecordsStoreTest, RunIsRecordedOnceWithItsUnitsAndSteps) {
  RecordsStore store(db_);
  EXPECT_TRUE(store.AddRun(Run("run-a", "aa")));
  EXPECT_FALSE(store.AddRun(Run("run-a", "aa")));
  EXPECT_TRUE(store.AddRun(Run("run-a", "bb")));  // the same run, resumed: a new recording state
  EXPECT_EQ(PythonQuery("SELECT count(*) FROM runs"), "[(2,)]\n");
  EXPECT_EQ(PythonQuery("SELECT serial, role, slot, constants_version FROM run_units ORDER BY "
                        "run, serial LIMIT 2"),
            "[('IMU-0001', 'imu1', 1, None), ('IMU-0002', 'imu2', 2, 3)]\n");
  EXPECT_EQ(PythonQuery("SELECT step_index, kind, tag, rejected_s FROM steps WHERE run = 1"),
            "[(0, 'prompt', 1, 0.0), (1, 'accel', 2, 1.5)]\n");
  const UnitHistory history = store.History("IMU-0002");
  EXPECT_EQ(history.kind, "imu");
  ASSERT_EQ(history.runs.size(), 2u);
  EXPECT_EQ(history.runs[0].recording_sha256, "aa");
  EXPECT_EQ(history.runs[1].role, "imu2");
}

TEST_F(RecordsStoreTest, ConstantsVersionsAreKeptAndNeverOverwritten) {
  RecordsStore store(db_);
  EXPECT_EQ(store.AddConstants(Constants("IMU-0001", "c1")), 1);
  EXPECT_EQ(store.AddConstants(Constants("IMU-0001", "c2")), 2);
  EXPECT_EQ(store.AddConstants(Constants("IMU-0001", "c1")), 1);  // same file again
  EXPECT_EQ(store.AddConstants(Constants("IMU-0002", "c1")), 1);  // versions count per unit
  EXPECT_EQ(PythonQuery("SELECT serial, version, file_sha256 FROM constants ORDER BY id"),
            "[('IMU-0001', 1, 'c1'), ('IMU-0001', 2, 'c2'), ('IMU-0002', 1, 'c1')]\n");
  // The database itself refuses to overwrite or delete a version, whoever asks.
  SqliteDatabase raw(db_, false);
  try {
    raw.Execute("UPDATE constants SET json = '{}' WHERE version = 1");
    FAIL() << "update accepted";
  } catch (const RecordsError& e) {
    EXPECT_THAT(e.what(), HasSubstr("never overwritten"));
    EXPECT_THAT(e.what(), HasSubstr(db_.string()));
  }
  EXPECT_THROW(raw.Execute("DELETE FROM constants"), RecordsError);
  EXPECT_EQ(PythonQuery("SELECT count(*) FROM constants"), "[(3,)]\n");
}

// A query never writes: an empty file, another SQLite database, or a database written by this
// program are opened read-only; the first two are refused by name and left as they were.
TEST_F(RecordsStoreTest, ReadingNeverWritesAndRefusesWhatIsNotARecordsDatabase) {
  const std::filesystem::path empty = dir_ / "empty.sqlite";
  std::ofstream(empty).close();
  try {
    RecordsStore::OpenForReading(empty);
    FAIL() << "an empty file was opened";
  } catch (const RecordsError& e) {
    EXPECT_THAT(e.what(), HasSubstr("not an adahrs records database"));
  }
  EXPECT_EQ(std::filesystem::file_size(empty), 0u);
  {
    RecordsStore store(db_);
    store.AddConstants(Constants("IMU-0001", "c1"));
  }
  const auto before = std::filesystem::last_write_time(db_);
  RecordsStore reader = RecordsStore::OpenForReading(db_);
  EXPECT_EQ(reader.History("IMU-0001").constants.size(), 1u);
  EXPECT_EQ(std::filesystem::last_write_time(db_), before);
}

// A refused file never becomes a constants version; an accepted one does, and a later refused
// attempt of the same file is recorded against it.
TEST_F(RecordsStoreTest, OnlyAcceptedFilesBecomeConstantsVersions) {
  RecordsStore store(db_);
  const DownloadRecord refused{"IMU-0001",
                               0,
                               "virtual lab",
                               "imu1",
                               false,
                               false,
                               std::nullopt,
                               std::nullopt,
                               "IMU-0002 answers on imu1: another unit's constants"};
  EXPECT_EQ(RecordDownloadAttempt(store, Constants("IMU-0001", "c1"), refused), std::nullopt);
  EXPECT_EQ(PythonQuery("SELECT count(*) FROM constants"), "[(0,)]\n");
  EXPECT_EQ(PythonQuery("SELECT count(*) FROM downloads"), "[(0,)]\n");

  DownloadRecord accepted = refused;
  accepted.verified = accepted.committed = true;
  accepted.detail = "ok";
  EXPECT_EQ(RecordDownloadAttempt(store, Constants("IMU-0001", "c1"), accepted), 1);
  EXPECT_EQ(RecordDownloadAttempt(store, Constants("IMU-0001", "c1"), refused), 1);
  EXPECT_EQ(RecordDownloadAttempt(store, Constants("IMU-0001", "c2"), refused), std::nullopt);
  EXPECT_EQ(PythonQuery("SELECT count(*) FROM constants"), "[(1,)]\n");
  EXPECT_EQ(PythonQuery("SELECT verified, committed FROM downloads ORDER BY rowid"),
            "[(1, 1), (0, 0)]\n");
}

TEST_F(RecordsStoreTest, HistoryShowsDownloadsAndAcceptanceVerdicts) {
  RecordsStore store(db_);
  store.AddConstants(Constants("IMU-0001", "c1"));
  store.AddConstants(Constants("IMU-0001", "c2"));
  store.AddDownload({"IMU-0001",
                     1,
                     "virtual lab",
                     "imu1",
                     false,
                     false,
                     std::nullopt,
                     std::nullopt,
                     "block 0x03 read back differs"});
  store.AddDownload(
      {"IMU-0001", 2, "virtual lab", "imu1", true, true, int64_t{1}, int64_t{0xBEEF}, "ok"});
  const std::vector<AcceptancePointRecord> points = {
      {"IMU-0001", "acc-1", "accel_x", "orientation 11", 0.0004, 0.001, "g", true, "PASS", "ab"},
      {"IMU-0001", "acc-1", "rate_z", "150 deg/s", 0.02, 0.015, "deg/s", false, "FAIL", "ab"}};
  EXPECT_TRUE(store.AddAcceptance("s1", points));
  EXPECT_FALSE(store.AddAcceptance("s1", points));

  const UnitHistory history = store.History("IMU-0001");
  ASSERT_EQ(history.constants.size(), 2u);
  EXPECT_EQ(history.constants[0].downloads, 1);
  EXPECT_FALSE(history.constants[0].committed);
  EXPECT_TRUE(history.constants[1].committed);
  EXPECT_EQ(history.constants[1].unit_constants_version, 1);
  EXPECT_EQ(history.constants[1].unit_constants_crc, 0xBEEF);
  ASSERT_EQ(history.acceptance.size(), 1u);
  EXPECT_EQ(history.acceptance[0].points, 2);
  EXPECT_EQ(history.acceptance[0].failed, 1);
  ASSERT_EQ(history.acceptance[0].failures.size(), 1u);
  EXPECT_EQ(history.acceptance[0].failures[0].quantity, "rate_z");
  EXPECT_DOUBLE_EQ(history.acceptance[0].failures[0].error, 0.02);
}

// A version 1 database (no outcome, no specification column) with one passing and one failing
// point: migrating keeps both rows, gives them the outcome their pass says and an unknown ('')
// specification, and new points carry both.
TEST_F(RecordsStoreTest, Version1AcceptanceRowsMigrateWithTheirOutcome) {
  { RecordsStore store(db_); }
  {
    SqliteDatabase raw(db_, false);
    raw.Execute(
        "ALTER TABLE acceptance_results DROP COLUMN specification_sha256;"
        "ALTER TABLE acceptance_results DROP COLUMN outcome;"
        "DROP TABLE acceptance_attempts;"
        "UPDATE schema_version SET version = 1;"
        "INSERT INTO units VALUES ('ADS-0001', 'ads', '2024-05-01T09:00:00Z');"
        "INSERT INTO acceptance_results (serial, source_sha256, run_id, quantity, condition, "
        "error, tolerance, unit, pass, recorded_utc) VALUES "
        "('ADS-0001', 'old', 'acc-0', 'altitude', 'step 1', 14.0, 15.0, 'ft', 1, 'x'), "
        "('ADS-0001', 'old', 'acc-0', 'airspeed', 'step 1', 2.5, 2.0, 'kt', 0, 'x');");
  }
  RecordsStore store(db_);
  EXPECT_EQ(PythonQuery("SELECT version FROM schema_version"), "[(3,)]\n");
  EXPECT_EQ(PythonQuery("SELECT quantity, pass, outcome, specification_sha256 FROM "
                        "acceptance_results ORDER BY id"),
            "[('altitude', 1, 'PASS', ''), ('airspeed', 0, 'FAIL', '')]\n");
  store.AddAcceptance(
      "new",
      {{"ADS-0001", "acc-1", "altitude", "step 1", 14.0, 15.0, "ft", true, "MARGINAL", "cd"}});
  const UnitHistory history = store.History("ADS-0001");
  ASSERT_EQ(history.acceptance.size(), 2u);
  EXPECT_EQ(history.acceptance[0].specification_sha256, "");
  EXPECT_EQ(history.acceptance[0].failed, 1);
  EXPECT_EQ(history.acceptance[1].specification_sha256, "cd");
  EXPECT_EQ(history.acceptance[1].marginal, 1);
}

TEST_F(RecordsStoreTest, FailedAddLeavesNothingBehind) {
  RecordsStore store(db_);
  RunRecord run = Run("run-b", "aa");
  run.units[1].kind = "ads";  // IMU-0002 cannot be an ADS: refused after the run row was inserted
  try {
    store.AddRun(run);
    FAIL() << "accepted";
  } catch (const RecordsError& e) {
    EXPECT_THAT(e.what(), HasSubstr(db_.string()));
    EXPECT_THAT(e.what(), HasSubstr("IMU-0002"));
  }
  EXPECT_EQ(PythonQuery("SELECT count(*) FROM runs"), "[(0,)]\n");
  EXPECT_EQ(PythonQuery("SELECT count(*) FROM units"), "[(0,)]\n");
}

TEST_F(RecordsStoreTest, ErrorsNameTheDatabaseFile) {
  RecordsStore store(db_);
  try {
    store.History("IMU-0404");
    FAIL();
  } catch (const RecordsError& e) {
    EXPECT_THAT(e.what(), HasSubstr(db_.string()));
    EXPECT_THAT(e.what(), HasSubstr("no unit IMU-0404"));
  }
  EXPECT_THROW(store.AddDownload({"IMU-0404", 1, "lab", "imu1", true, true, {}, {}, "ok"}),
               RecordsError);
  const auto missing = dir_ / "no_such_dir" / "x.sqlite";
  try {
    RecordsStore bad(missing);
    FAIL();
  } catch (const RecordsError& e) {
    EXPECT_THAT(e.what(), HasSubstr(missing.string()));
  }
}

TEST_F(RecordsStoreTest, DatabaseFromANewerProgramIsRefused) {
  { RecordsStore store(db_); }
  {
    SqliteDatabase raw(db_, false);
    raw.Execute("UPDATE schema_version SET version = 99");
  }
  try {
    RecordsStore store(db_);
    FAIL();
  } catch (const RecordsError& e) {
    EXPECT_THAT(e.what(), HasSubstr("schema version 99 is newer"));
    EXPECT_THAT(e.what(), HasSubstr(db_.string()));
  }
}

}  // namespace
}  // namespace adahrs::calib
