#include "calib/executor/journal.h"

#include <unistd.h>

#include <fstream>
#include <variant>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/executor/resume_point.h"

namespace adahrs::calib {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

class JournalTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("adahrs_journal_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(JournalTest, AppendsAcrossReopenAndToleratesATornLastLine) {
  {
    Journal j(dir_);
    j.Append(RunStarted{0.0, "2026-12-06T18:00:00Z", 0, false});
    j.Append(ActionStarted{1.0, 0, 0, "chamber to 25 degC"});
    j.Sync();
  }
  {
    Journal j(dir_);
    j.Append(StepCompleted{2.0, 0});
    j.Sync();
  }
  std::ofstream(dir_ / kJournalName, std::ios::app) << R"({"event":"action_sta)";  // crash
  const JournalContents c = ReadJournal(dir_);
  ASSERT_EQ(c.events.size(), 3u);
  ASSERT_TRUE(std::holds_alternative<StepCompleted>(c.events[2]));
  EXPECT_EQ(std::get<StepCompleted>(c.events[2]).t_s, 2.0);
  EXPECT_EQ(std::get<ActionStarted>(c.events[1]).action, "chamber to 25 degC");
  EXPECT_EQ(c.torn_lines, 1);
}

TEST_F(JournalTest, ABadCompleteLineNamesTheLineAndTheField) {
  const auto error_of = [&](const std::string& second_line) {
    std::ofstream(dir_ / kJournalName)
        << R"({"event":"run_started","t_s":0,"utc":"2026-12-06T18:00:00Z","first_step":0})"
        << "\n"
        << second_line << "\n";
    try {
      ReadJournal(dir_);
    } catch (const JournalError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(error_of("[1,2]"), HasSubstr("journal.jsonl:2: not an object"));
  EXPECT_THAT(error_of(R"({"event":"step_completed","step":-1,"t_s":3.0})"),
              HasSubstr("journal.jsonl:2: step_completed: $.step: value -1 out of range"));
  EXPECT_THAT(error_of(R"({"event":"action_started","step":1.5,"t_s":3.0,"index":0,"action":"x"})"),
              HasSubstr("journal.jsonl:2: action_started: $.step: expected an integer"));
  EXPECT_THAT(error_of(R"({"event":"interlock_failed","step":1,"t_s":3.0})"),
              HasSubstr("journal.jsonl:2: interlock_failed: $.interlock: missing key"));
  EXPECT_THAT(error_of(R"({"event":"step_exploded","t_s":3.0})"),
              HasSubstr("journal.jsonl:2: step_exploded: not an event of this journal"));
  EXPECT_EQ(error_of(R"({"event":"step_completed","step":1,"t_s":3.0})"), "accepted");
}

// Every event survives its JSON line: what the executor journals is what a resume reads.
TEST_F(JournalTest, EveryEventRoundTripsThroughItsLine) {
  const std::vector<JournalEvent> events = {
      RunStarted{0.5, "2026-12-06T18:00:00Z", 2, true},
      TornTailSetAside{0.6, "imu.csv", "imu.csv.torn-1"},
      RigSafeAtStart{0.7, 50.25},
      RigSafeAtStart{0.8, std::nullopt},
      StepRepeated{1.0, 2, 0.25},
      ActionStarted{1.5, 7, 2, "table to 100 deg/s"},
      ActionCompleted{2.0, 7, 2},
      StepCompleted{2.5, 2},
      InterlockFailed{3.0, 3, "gravity", 2, {"IMU-0001: 0.41 g", "IMU-0003: 0.02 g"}},
      StateRestored{3.5},
      SafeStopFailed{4.0, "table stop", "no reply"},
      RigSafe{4.5},
      RunStopped{5.0, 9, "stop requested", false},
      RunStopped{5.5, 9, "chamber lost", true},
      RunCompleted{6.0}};
  {
    Journal j(dir_);
    for (const JournalEvent& e : events) j.Append(e);
  }
  const JournalContents c = ReadJournal(dir_);
  ASSERT_EQ(c.events.size(), events.size());
  for (size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(ToJson(c.events[i]), ToJson(events[i])) << i;
    EXPECT_EQ(c.events[i].index(), events[i].index()) << i;
  }
  EXPECT_EQ(EventName(c.events[12]), "interrupted");
  EXPECT_EQ(EventName(c.events[13]), "aborted");
  EXPECT_EQ(std::get<InterlockFailed>(c.events[8]).units[1], "IMU-0003: 0.02 g");
}

// Steps complete in order; the first one without step_completed is where a resume starts, and its
// first action's start is where its repeated rows begin.
TEST(ResumePoint, FirstIncompleteStepAndWhenItBegan) {
  JournalContents j;
  j.events = {RunStarted{0.5, "", 0, false},
              ActionStarted{1.0, 0, 0, ""},
              StepCompleted{5.0, 0},
              ActionStarted{5.5, 1, 1, ""},
              ActionCompleted{7.0, 1, 1},
              ActionStarted{7.5, 2, 1, ""}};
  const ResumePoint p = FindResumePoint(j, 3);
  EXPECT_EQ(p.first_incomplete_step, 1u);
  ASSERT_TRUE(p.interrupted_step_started_s.has_value());
  EXPECT_EQ(*p.interrupted_step_started_s, 5.5);
  EXPECT_EQ(p.last_t_s, 7.5);
  EXPECT_FALSE(p.run_completed);
}

// A corrupt journal is refused by event, never trusted: a time of 1e308 once set the resumed
// clock so far ahead that the resume waited forever. (A step that is no index, -1 or 1.5, is
// refused by the reader: ABadCompleteLineNamesTheLineAndTheField.)
TEST(ResumePoint, RefusesImpossibleTimesAndSteps) {
  const auto error_of = [](const JournalEvent& bad) {
    JournalContents j;
    j.events = {RunStarted{0.5, "", 0, false}, StepCompleted{2.0, 0}, bad};
    try {
      FindResumePoint(j, 3);
    } catch (const JournalError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(
      error_of(StepCompleted{1e308, 1}),
      AllOf(HasSubstr("journal event 3 (step_completed)"), HasSubstr("not a time of a run")));
  EXPECT_THAT(error_of(StepCompleted{3.0, 3}),
              AllOf(HasSubstr("journal event 3"),
                    HasSubstr("\"step\" 3 is not a step of the sequence (0 ... 2)")));
  EXPECT_THAT(error_of(ActionStarted{3.0, 0, 7, ""}), HasSubstr("\"step\" 7"));
  EXPECT_THAT(error_of(StepCompleted{1.0, 1}), HasSubstr("before the previous"));
  EXPECT_EQ(error_of(StepCompleted{3.0, 1}), "accepted");
}

TEST(ResumePoint, RefusesAJournalWithoutRunStarted) {
  JournalContents j;
  j.events = {StepCompleted{5.0, 0}};
  EXPECT_THROW(FindResumePoint(j, 2), JournalError);
}

}  // namespace
}  // namespace adahrs::calib
