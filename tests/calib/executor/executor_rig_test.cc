// The executor against the virtual rig as a separate process (the production code path: station
// file, serial ports, drivers). Expected values come from the sequence (N, orientations, rates)
// and the rig's own report of its physics (control port `env`), never from the executor.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>

#include <gmock/gmock.h>
#include <cstdio>

#include <gtest/gtest.h>

#include "calib/executor/journal.h"
#include "calib/executor/run_session.h"
#include "hil/drivers/station_instruments.h"
#include "tests/calib/executor/executor_test_util.h"
#include "tests/support/sanitized_units.h"

namespace adahrs::calib {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::RecordingProgress;
using testing::TempDir;

// 200x: the sequence's ~2 simulated minutes take under a second of wall time, well inside the
// rig's loss-free range (docs/performance.md), on 2 shared cores.
constexpr double kTimeScale = 200.0;

const nlohmann::json kShortImuSteps = nlohmann::json::parse(R"([
  {"kind": "target_temperature", "target_c": 25.0, "band_c": 1.0, "soak_s": 10.0},
  {"kind": "accel", "orientation": 11, "packets": 200},
  {"kind": "accel", "orientation": 32, "packets": 200},
  {"kind": "gyro", "orientation": 31, "packets": 100, "rate_min_dps": -100, "rate_max_dps": 100,
   "rate_increment_dps": 100, "table_accel_dps2": 100}
])");

TEST(ExecutorRig, ShortImuSequenceRecordsExactlyTheAcquisitionsOfFourUnits) {
  adahrs::testing::RigProcess rig(kTimeScale);
  TempDir dir("short");
  NewRunOptions options;
  options.station_file = rig.WriteStation();
  options.sequence_file = testing::WriteSequence(dir.path(), "imu", kShortImuSteps);
  options.run_dir = dir.path() / "run";
  RecordingProgress progress;
  std::atomic<bool> stop{false};
  const RunSummary summary = StartRun(options, progress, stop);
  EXPECT_EQ(summary.status, "complete");
  EXPECT_EQ(summary.lost, 0u);

  const hil::Recording rec = hil::ReadRecording(options.run_dir);
  EXPECT_EQ(rec.meta.status.value_or(""), "complete");
  EXPECT_EQ(rec.meta.units.size(), 4u);
  EXPECT_TRUE(rec.meta.rejected_intervals.empty());
  EXPECT_EQ(rec.imu.size(), summary.rows);
  for (const auto& [unit, gaps] : testing::SequenceGaps(rec)) EXPECT_EQ(gaps, 0) << unit;

  const auto tagged = testing::TaggedImuRows(rec);
  for (int u = 1; u <= 4; ++u) {
    const std::string serial = "IMU-000" + std::to_string(u);
    EXPECT_FALSE(tagged.contains({serial, 1})) << "target_temperature acquires nothing";
    const auto& accel11 = tagged.at({serial, 2});
    const auto& accel32 = tagged.at({serial, 3});
    const auto& gyro = tagged.at({serial, 4});
    EXPECT_EQ(accel11.size(), 200u) << serial;
    EXPECT_EQ(accel32.size(), 200u) << serial;
    ASSERT_EQ(gyro.size(), 300u) << serial;  // 3 rates x 100
    for (const auto& r : accel11) EXPECT_EQ(r.orientation, 11);
    for (const auto& r : accel32) EXPECT_EQ(r.orientation, 32);
    // Each rate's acquisition: the table's reported rate within 0.01 deg/s of the command.
    std::map<long, int> per_rate;
    for (const auto& r : gyro) {
      EXPECT_EQ(r.orientation, 31);
      const long command = std::lround(r.table_rate_dps / 100.0) * 100;
      EXPECT_NEAR(r.table_rate_dps, static_cast<double>(command), 0.01);
      ++per_rate[command];
    }
    EXPECT_EQ(per_rate, (std::map<long, int>{{-100, 100}, {0, 100}, {100, 100}})) << serial;
  }
  EXPECT_NEAR(testing::RigTableRateDps(rig), 0.0, 1e-9);
}

// Runs the short IMU sequence on `station_file` with imu2 turned back to 31 (the wrong way up)
// after every mount in 32; returns the RunError's text ("" and a failure if the run completed).
std::string RunWithImu2TurnedBack(const adahrs::testing::RigProcess& rig,
                                  const TempDir& dir,
                                  const std::string& station_file,
                                  std::string* reply) {
  NewRunOptions options;
  options.station_file = station_file;
  options.sequence_file = testing::WriteSequence(dir.path(), "imu", kShortImuSteps);
  options.run_dir = dir.path() / "run";
  options.wrap_operator =
      testing::DisturbingOperator::Wrapper(rig, 32, "orientation imu2 31", *reply);
  RecordingProgress progress;
  std::atomic<bool> stop{false};
  try {
    StartRun(options, progress, stop);
  } catch (const RunError& e) {
    return e.what();
  }
  ADD_FAILURE() << "the run should have stopped";
  return "";
}

TEST(ExecutorRig, WrongOrientationStopsTheRunAndTagsNothing) {
  adahrs::testing::RigProcess rig(kTimeScale);
  TempDir dir("interlock");
  std::string reply;
  const std::string error = RunWithImu2TurnedBack(rig, dir, rig.WriteStation(), &reply);
  EXPECT_THAT(error,
              AllOf(HasSubstr("step 2 (accel"),
                    HasSubstr("gravity interlock failed"),
                    HasSubstr("imu2 (IMU-0002)")));
  EXPECT_THAT(error, ::testing::Not(HasSubstr("imu1")));
  EXPECT_EQ(reply, "OK imu2 31");
  const hil::Recording rec = hil::ReadRecording(dir.path() / "run");
  EXPECT_EQ(rec.meta.status.value_or(""), "aborted");
  ASSERT_EQ(rec.meta.rejected_intervals.size(), 3u);  // every attempt
  for (const auto& r : rec.meta.rejected_intervals) EXPECT_EQ(r.step, 2);
  for (const auto& r : rec.imu) EXPECT_NE(r.tag, 3) << "no row tagged for step 2";
  EXPECT_EQ(testing::TaggedImuRows(rec).at({"IMU-0002", 2}).size(), 200u);  // step 1 kept
  EXPECT_NEAR(testing::RigTableRateDps(rig), 0.0, 1e-9);
}

// The station file's interlock attempts bound the retries: one attempt, one rejected interval,
// where the default's three gave three above.
TEST(ExecutorRig, TheStationsInterlockAttemptsBoundTheRetries) {
  adahrs::testing::RigProcess rig(kTimeScale);
  TempDir dir("interlock_attempts");
  std::string reply;
  const std::string station = rig.WriteStation("station.json", [](nlohmann::json& j) {
    j["interlocks"] = {{"attempts", 1}};
  });
  EXPECT_THAT(
      RunWithImu2TurnedBack(rig, dir, station, &reply),
      AllOf(HasSubstr("gravity interlock failed (attempt 1 of 1)"), HasSubstr("imu2 (IMU-0002)")));
  const hil::Recording rec = hil::ReadRecording(dir.path() / "run");
  EXPECT_EQ(rec.meta.status.value_or(""), "aborted");
  EXPECT_EQ(rec.meta.rejected_intervals.size(), 1u);
  EXPECT_NEAR(testing::RigTableRateDps(rig), 0.0, 1e-9);
}

// A killed run leaves the table turning: the next run stops it before its first step, so no
// accelerometer row is acquired on a spinning table.
TEST(ExecutorRig, ATableLeftTurningIsStoppedBeforeTheFirstStep) {
  adahrs::testing::RigProcess rig(kTimeScale);
  TempDir dir("turning");
  NewRunOptions options;
  options.station_file = rig.WriteStation();
  {
    const hil::Station station = hil::Station::Load(options.station_file);
    const std::unique_ptr<hil::Clock> clock =
        hil::MakeClock(station.time_scale, station.clock_file);
    hil::StationInstruments left = hil::OpenStation(station, *clock);
    left.rate_table->CommandRate(50.0, 100.0);
    clock->SleepS(5.0);
  }
  ASSERT_NEAR(testing::RigTableRateDps(rig), 50.0, 0.1);
  options.sequence_file = testing::WriteSequence(dir.path(), "imu", nlohmann::json::parse(R"([
    {"kind": "accel", "orientation": 11, "packets": 200}])"));
  options.run_dir = dir.path() / "run";
  RecordingProgress progress;
  std::atomic<bool> stop{false};
  EXPECT_EQ(StartRun(options, progress, stop).status, "complete");
  const hil::Recording rec = hil::ReadRecording(options.run_dir);
  const auto tagged = testing::TaggedImuRows(rec);
  ASSERT_EQ(tagged.at({"IMU-0001", 1}).size(), 200u);
  for (const auto& r : tagged.at({"IMU-0001", 1})) ASSERT_NEAR(r.table_rate_dps, 0.0, 0.01);
  const JournalContents journal = ReadJournal(options.run_dir);
  const auto safe = std::find_if(journal.events.begin(), journal.events.end(), [](const auto& e) {
    return std::holds_alternative<RigSafeAtStart>(e);
  });
  ASSERT_NE(safe, journal.events.end());
  ASSERT_TRUE(std::get<RigSafeAtStart>(*safe).table_found_dps.has_value());
  EXPECT_NEAR(*std::get<RigSafeAtStart>(*safe).table_found_dps, 50.0, 0.1);
  EXPECT_THAT(progress.notes, ::testing::Contains(HasSubstr("rate table found turning at 50")));
}

// A first temperature step whose chamber starts far from where the plan assumed (25 degC): the
// wait is budgeted from the chamber's own process value. The F4 holds 0 degC at power-up; the
// step asks for 25 degC, which the plan estimated at its 10 s soak alone: 3 x 10 s + the margin
// would abort it minutes before the air arrives (a 5 degC/min ramp, then the loop's tail).
// The progress ETA measures the chamber's approach instead (chamber_eta.h), checked against when
// the wait really ended (the journal): while the air settles onto the set point (the last 40 % of
// the wait) within 30 % of the time really left, or 30 s near the band: the air's residual
// control cycling (+-0.3 degC, docs/rig/watlow-f4.md) at the closing slope of the last degree
// (about 1 degC / 120 s) moves the band's entry by that much; during the ramp before it, which
// cannot show the settling to come, nearer the time left than the plan's (under 10 s).
TEST(ExecutorRig, AFirstChamberStepFarFromThePlansStartIsWaitedFor) {
  auto config = nlohmann::json::parse(adahrs::testing::RigProcess(kTimeScale).config().dump());
  config["instruments"]["watlow_f4"]["controller"]["static_set_point_c"] = 0.0;
  config["instruments"]["watlow_f4"]["chamber"]["initial_air_c"] = 0.0;
  adahrs::testing::RigProcess rig(kTimeScale / 2, config);
  TempDir dir("far_chamber");
  NewRunOptions options;
  options.station_file = rig.WriteStation();
  options.sequence_file = testing::WriteSequence(dir.path(), "imu", nlohmann::json::parse(R"([
    {"kind": "target_temperature", "target_c": 25.0, "band_c": 1.0, "soak_s": 10.0}])"));
  options.run_dir = dir.path() / "run";
  options.executor.progress_interval_s = 0.1;  // wall: about one report per 10 s of the wait
  RecordingProgress progress;
  std::atomic<bool> stop{false};
  StartRun(options, progress, stop);
  const hil::Recording rec = hil::ReadRecording(options.run_dir);
  EXPECT_EQ(rec.meta.status.value_or(""), "complete");
  ASSERT_FALSE(rec.imu.empty());
  double first_c = 0.0;  // the first reported temperature (rows before the first report carry 0)
  for (const auto& r : rec.imu) {
    if (r.chamber_c != 0.0) {
      first_c = r.chamber_c;
      break;
    }
  }
  std::printf("chamber from %.1f degC to %.1f degC over %.0f s\n",
              first_c,
              rec.imu.back().chamber_c,
              rec.imu.back().t_s - rec.imu.front().t_s);
  EXPECT_LT(first_c, 5.0);  // it did start far away
  EXPECT_NEAR(rec.imu.back().chamber_c, 25.0, 1.0);

  double started_s = -1.0, ended_s = -1.0;  // the chamber wait, by the journal
  size_t wait = 0;
  for (const JournalEvent& e : ReadJournal(options.run_dir).events) {
    if (const auto* a = std::get_if<ActionStarted>(&e);
        a && a->action.find("soak") != std::string::npos) {
      started_s = a->t_s;
      wait = a->index;
    }
    if (const auto* c = std::get_if<ActionCompleted>(&e); c && started_s >= 0.0 && c->index == wait)
      ended_s = c->t_s;
  }
  ASSERT_GT(ended_s, started_s + 200.0) << "the wait lasted no ramp";
  // Under the sanitizers the executor reads the chamber several times less often per simulated
  // second (a wall-time minimum poll at a 100x clock): 120 s windows then hold too few readings to
  // tell a ramp from the settling, and this pass looks for memory errors, not the ETA's figure,
  // which the release pass holds.
  if (adahrs::testing::kSanitized) return;
  int ramp = 0, settling = 0;
  // A report is due every 10 s of the wait; one that comes later (the executor descheduled on a
  // loaded machine) may carry an estimate from a chamber reading as old as its gap to the one
  // before, so the settling bound allows the gap beyond the interval on top.
  double previous_s = started_s;
  for (const ProgressReport& r : progress.reports) {
    const double late_s = std::max(0.0, r.t_s - previous_s - 10.0);
    previous_s = r.t_s;
    const double done = (r.t_s - started_s) / (ended_s - started_s);
    const double left_s = ended_s - r.t_s;
    const double plan_left_s = std::max(0.0, 10.0 - (r.t_s - started_s));
    std::printf(
        "%5.0f s into the wait: ETA %5.0f s, left %5.0f s\n", r.t_s - started_s, r.eta_s, left_s);
    if (done > 0.1 && done < 0.4) {
      EXPECT_LT(std::abs(r.eta_s - left_s), std::abs(plan_left_s - left_s));
      ++ramp;
    } else if (done >= 0.6) {
      EXPECT_NEAR(r.eta_s, left_s, std::max(0.3 * left_s, 30.0) + late_s)
          << "at " << r.t_s - started_s;
      ++settling;
    }
  }
  EXPECT_GE(ramp, 1);
  EXPECT_GE(settling, 1);
}

// thermal_profile: the TAG is on for the whole profile run, so every packet of the run is tagged,
// in one block per unit, while the chamber follows the profile (PV as the F4 reports it).
TEST(ExecutorRig, ThermalProfileTagsEveryPacketWhileTheProfileRuns) {
  // The F4 ramps from its process value (INF); without the air's residual cycling (+-0.3 degC
  // about the 25 degC set point, docs/rig/watlow-f4.md) that is 25 degC whenever the run starts,
  // so the profile lasts exactly 80 s.
  auto config = nlohmann::json::parse(adahrs::testing::RigProcess(kTimeScale).config().dump());
  config["instruments"]["watlow_f4"]["chamber"]["control_band_c"] = 0.0;
  adahrs::testing::RigProcess rig(kTimeScale / 2, config);  // 100x: the profile in under a second
  TempDir dir("profile");
  NewRunOptions options;
  options.station_file = rig.WriteStation();
  options.sequence_file = testing::WriteSequence(dir.path(), "imu", nlohmann::json::parse(R"([
    {"kind": "thermal_profile", "profile_name": "EXEC TEST", "profile_steps": [
      {"type": "ramp_rate", "target_c": 30.0, "rate_c_per_min": 5.0},
      {"type": "soak", "duration_s": 20.0},
      {"type": "end", "action": "hold"}]}])"));
  options.run_dir = dir.path() / "run";
  RecordingProgress progress;
  std::atomic<bool> stop{false};
  EXPECT_EQ(StartRun(options, progress, stop).lost, 0u);
  const hil::Recording rec = hil::ReadRecording(options.run_dir);
  const auto tagged = testing::TaggedImuRows(rec);
  for (int u = 1; u <= 4; ++u) {
    const std::string serial = "IMU-000" + std::to_string(u);
    const auto& rows = tagged.at({serial, 1});
    // 25 -> 30 degC at 5 degC/min is 60 s, then 20 s of soak: 8,000 packets at 100 Hz. The TAG
    // is on before the profile starts and off after the executor has seen it end.
    EXPECT_GE(rows.size(), 8000u) << serial;
    double max_c = -100.0;
    for (const auto& r : rows) max_c = std::max(max_c, r.chamber_c);
    // The chamber air follows the 5 degC rise with a lag (docs/rig/watlow-f4.md): its PV, as the
    // rows record it, climbs by more than a degree and never beyond the profile's 30 degC band.
    EXPECT_GT(max_c, rows.front().chamber_c + 1.0) << serial;
    EXPECT_LT(max_c, 31.0) << serial;
    // One block: no untagged row of this unit between its first and last tagged row.
    size_t first = rec.imu.size(), last = 0, inside = 0;
    for (size_t i = 0; i < rec.imu.size(); ++i) {
      if (rec.imu[i].unit != serial || rec.imu[i].tag != 1) continue;
      first = std::min(first, i);
      last = i;
    }
    for (size_t i = first; i <= last; ++i) inside += rec.imu[i].unit == serial ? 1 : 0;
    EXPECT_EQ(inside, rows.size()) << serial;
  }
}

// ADS batch: the air data test set's aims, each log step's N packets per unit, the reference
// columns what the ADTS reports. Expected pressures from the ISA (independent formulas):
//   ps(h) = 101325 Pa (1 - 6.8755856e-6 h/ft)^5.2558797,
//   qc(V) = 101325 Pa ((1 + 0.2 (V / 661.4786 kt)^2)^3.5 - 1).
TEST(ExecutorRig, AdsBatchLogsAtTheTestSetsAims) {
  adahrs::testing::RigProcess rig(kTimeScale);
  TempDir dir("ads");
  NewRunOptions options;
  options.station_file = rig.WriteStation();
  options.sequence_file = testing::WriteSequence(dir.path(), "ads", nlohmann::json::parse(R"([
    {"kind": "altitude", "alt_ft": 2000.0, "rate_ft_per_min": 6000.0},
    {"kind": "log", "packets": 100},
    {"kind": "airspeed", "cas_kt": 100.0, "rate_kt_per_min": 200.0},
    {"kind": "log", "packets": 100}])"));
  options.run_dir = dir.path() / "run";
  RecordingProgress progress;
  std::atomic<bool> stop{false};
  EXPECT_EQ(StartRun(options, progress, stop).lost, 0u);
  const hil::Recording rec = hil::ReadRecording(options.run_dir);
  const double ps_2000ft_pa = 101325.0 * std::pow(1.0 - 6.8755856e-6 * 2000.0, 5.2558797);
  const double qc_100kt_pa =
      101325.0 * (std::pow(1.0 + 0.2 * std::pow(100.0 / 661.4786, 2), 3.5) - 1.0);
  std::map<int, int> per_tag;
  for (const auto& r : rec.ads) {
    if (r.tag == 0) continue;
    ++per_tag[r.tag];
    // 30 Pa: the test set's control noise is +-3.8 Pa Ps, +-4.5 Pa Qc (3 sigma, docs/rig/adts.md);
    // the rest covers rounding of the ISA constants between these formulas and the rig's.
    EXPECT_NEAR(r.ps_ref_pa, ps_2000ft_pa, 30.0);
    EXPECT_NEAR(r.qc_ref_pa, r.tag == 2 ? 0.0 : qc_100kt_pa, 30.0);
  }
  // Steps: altitude (tag 1), log (2), airspeed (3), log (4); one ADS unit.
  EXPECT_EQ(per_tag, (std::map<int, int>{{2, 100}, {4, 100}}));
  EXPECT_EQ(rec.meta.units[0].serial, "ADS-0001");
}

}  // namespace
}  // namespace adahrs::calib
