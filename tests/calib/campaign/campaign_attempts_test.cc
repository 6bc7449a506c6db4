// The retest rules (calib/campaign/campaign_attempts.h, docs/campaign.md "Retests"): only units
// whose outcome is FAIL are retested (MARGINAL passes), each retest in its own directory on a
// station naming only those units, and a resumed judgement keeps the acceptance files it wrote.
#include "calib/campaign/campaign_attempts.h"

#include <unistd.h>

#include <cmath>

#include <gtest/gtest.h>

#include "calib/acceptance/acceptance_file.h"

namespace adahrs::calib {
namespace {

// One acceleration point of `error_mg` against a 1 mg tolerance with a 10 % marginal band: the
// outcome the specification gives it is PASS below 0.9 mg, MARGINAL to 1 mg, FAIL beyond.
UnitAcceptance Unit(const std::string& serial, double error_mg) {
  AcceptancePoint p;
  p.kind = "accel";
  p.quantity = "accel_x";
  p.unit = "mg";
  p.samples = 100;
  p.error = error_mg;
  p.tolerance = 1.0;
  p.marginal_band = 0.1;
  p.pass = std::abs(error_mg) <= 1.0;
  return {serial, "imu", 3, {p}, std::nullopt};
}

TEST(CampaignAttempts, OnlyFailedUnitsAreRetested) {
  AcceptanceRun run;
  run.units = {Unit("IMU-0001", 0.2), Unit("IMU-0002", 0.95), Unit("IMU-0003", 1.4)};
  const std::map<std::string, std::string> roles = {
      {"IMU-0001", "imu1"}, {"IMU-0002", "imu2"}, {"IMU-0003", "imu3"}};
  ASSERT_EQ(run.units[1].outcome(), Outcome::kMarginal);
  EXPECT_EQ(FailedRoles(run, roles), std::set<std::string>{"imu3"});
  run.units.push_back(Unit("IMU-0009", 2.0));  // judged, but downloaded by no station
  EXPECT_THROW(FailedRoles(run, roles), std::runtime_error);
}

TEST(CampaignAttempts, ARetestRunsInItsOwnDirectoryOnTheFailedUnitsOnly) {
  EXPECT_EQ(AttemptRunDir("/c/runs/imu_acceptance", 1), "/c/runs/imu_acceptance");
  EXPECT_EQ(AttemptRunDir("/c/runs/imu_acceptance", 2), "/c/runs/imu_acceptance-attempt2");
  hil::Station station;
  station.name = "bench";
  for (const char* role : {"imu1", "imu2", "imu3", "imu4"}) {
    hil::UnitEntry u;
    u.role = role;
    station.units.push_back(u);
  }
  const hil::Station kept = StationWithRoles(station, {"imu2", "imu4"});
  ASSERT_EQ(kept.units.size(), 2u);
  EXPECT_EQ(kept.units[0].role, "imu2");
  EXPECT_EQ(kept.units[1].role, "imu4");
  EXPECT_EQ(kept.name, "bench");
}

TEST(CampaignAttempts, AResumedJudgementKeepsTheFilesItWrote) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("adahrs-attempts-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  AcceptanceRun run;
  run.run_id = "run-1";
  run.units = {Unit("IMU-0001", 0.2), Unit("IMU-0002", 1.4)};
  const Specification spec = Specification::Reference();
  const auto written = AcceptanceFilesOf(run, spec, "test", dir);
  ASSERT_EQ(written.size(), 2u);
  const auto time = std::filesystem::last_write_time(written[1]);
  // Written again: the same paths, the files untouched.
  EXPECT_EQ(AcceptanceFilesOf(run, spec, "test", dir), written);
  EXPECT_EQ(std::filesystem::last_write_time(written[1]), time);
  const auto records =
      AttemptRecords("c1", 2, run, written, {{"IMU-0001", "imu1"}, {"IMU-0002", "imu2"}});
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[1].role, "imu2");
  EXPECT_EQ(records[1].outcome, "FAIL");
  EXPECT_EQ(records[1].attempt, 2);
  EXPECT_EQ(records[1].source_sha256.size(), 64u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace adahrs::calib
