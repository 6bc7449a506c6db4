// Acceptance attempts and yield from the records: the yields are counted by hand from the
// attempts written here (the truth), and the table is read back by Python's own sqlite3 module.
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/records/records_store.h"
#include "tests/support/python_sqlite.h"

namespace adahrs::calib {
namespace {

using ::testing::HasSubstr;

class YieldRecordsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("adahrs_yield_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    db_ = dir_ / "records.sqlite";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::pair<std::string, int> Python(const std::string& sql) {
    return adahrs::testing::PythonSqlite(db_, sql, dir_);
  }

  static AcceptanceAttemptRecord Attempt(const std::string& campaign,
                                         const std::string& serial,
                                         int attempt,
                                         const std::string& outcome) {
    return {campaign,
            serial,
            "role-" + serial,
            attempt,
            "run-" + std::to_string(attempt),
            serial + "-" + std::to_string(attempt),
            outcome};
  }

  std::filesystem::path dir_;
  std::filesystem::path db_;
};

// Four units: A passes at once, B fails then passes, C fails twice, D is MARGINAL at once.
// First-pass yield: A and D, 2 of 4. Final yield: A, B and D, 3 of 4. B and C retested, 6 attempts.
TEST_F(YieldRecordsTest, FirstPassAndFinalYieldCountEachUnitOnce) {
  RecordsStore store(db_);
  for (const auto& a : {Attempt("c1", "IMU-0001", 1, "PASS"),
                        Attempt("c1", "IMU-0002", 1, "FAIL"),
                        Attempt("c1", "IMU-0003", 1, "FAIL"),
                        Attempt("c1", "ADS-0001", 1, "MARGINAL"),
                        Attempt("c1", "IMU-0002", 2, "PASS"),
                        Attempt("c1", "IMU-0003", 2, "FAIL"),
                        // Another campaign on the same database stays apart.
                        Attempt("c2", "IMU-0003", 1, "PASS")}) {
    EXPECT_TRUE(store.AddAcceptanceAttempt(a));
  }
  const std::vector<CampaignYield> c1 = store.Yields("c1");
  ASSERT_EQ(c1.size(), 1u);
  EXPECT_EQ(c1[0].judged(), 4);
  EXPECT_EQ(c1[0].first_pass(), 2);
  EXPECT_EQ(c1[0].final_pass(), 3);
  EXPECT_EQ(c1[0].retested(), 2);
  EXPECT_EQ(c1[0].attempts(), 6);
  EXPECT_THAT(c1[0].Text(), HasSubstr("first-pass yield 2 of 4 (50.0 %"));
  EXPECT_THAT(c1[0].Text(), HasSubstr("final yield 3 of 4 (75.0 %"));
  EXPECT_EQ(c1[0].ToJson()["final_pass"], 3);

  const std::vector<CampaignYield> all = store.Yields();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[1].campaign, "c2");
  EXPECT_EQ(all[1].first_pass(), 1);
  EXPECT_EQ(all[1].judged(), 1);

  EXPECT_EQ(Python("SELECT serial, attempt, outcome FROM acceptance_attempts WHERE campaign = "
                   "'c1' AND serial = 'IMU-0002' ORDER BY attempt")
                .first,
            "[('IMU-0002', 1, 'FAIL'), ('IMU-0002', 2, 'PASS')]\n");
}

TEST_F(YieldRecordsTest, AnAttemptIsRecordedOnceAndNeverChanged) {
  RecordsStore store(db_);
  const AcceptanceAttemptRecord a = Attempt("c1", "IMU-0001", 1, "FAIL");
  EXPECT_TRUE(store.AddAcceptanceAttempt(a));
  EXPECT_FALSE(store.AddAcceptanceAttempt(a));  // the same file again: nothing changes
  AcceptanceAttemptRecord other = a;
  other.source_sha256 = "another file";
  EXPECT_THROW(store.AddAcceptanceAttempt(other), RecordsError);
  AcceptanceAttemptRecord bad = a;
  bad.attempt = 2;
  bad.outcome = "pass";
  EXPECT_THROW(store.AddAcceptanceAttempt(bad), RecordsError);
  bad.outcome = "PASS";
  bad.attempt = 0;
  EXPECT_THROW(store.AddAcceptanceAttempt(bad), RecordsError);
  // Evidence: another program cannot rewrite or delete an attempt either.
  const auto update = Python("UPDATE acceptance_attempts SET outcome = 'PASS'");
  EXPECT_EQ(update.second, 3) << update.first;
  EXPECT_THAT(update.first, HasSubstr("never updated"));
  const auto remove = Python("DELETE FROM acceptance_attempts");
  EXPECT_EQ(remove.second, 3) << remove.first;
  EXPECT_EQ(store.Yields("c1")[0].attempts(), 1);
}

TEST_F(YieldRecordsTest, AnUnknownCampaignIsRefusedNamingIt) {
  RecordsStore store(db_);
  EXPECT_TRUE(store.Yields().empty());
  try {
    store.Yields("2026-12-07T10:00:00Z-0000abcd");
    FAIL() << "no error";
  } catch (const RecordsError& e) {
    EXPECT_THAT(e.what(), HasSubstr("2026-12-07T10:00:00Z-0000abcd"));
    EXPECT_THAT(e.what(), HasSubstr(db_.string()));
  }
}

}  // namespace
}  // namespace adahrs::calib
