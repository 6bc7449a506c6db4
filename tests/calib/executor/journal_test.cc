#include "calib/executor/journal.h"

#include <unistd.h>

#include <fstream>

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
    j.Append({{"event", "run_started"}, {"t_s", 0.0}});
    j.Append({{"event", "action_started"}, {"t_s", 1.0}, {"step", 0}, {"index", 0}});
    j.Sync();
  }
  {
    Journal j(dir_);
    j.Append({{"event", "step_completed"}, {"t_s", 2.0}, {"step", 0}});
    j.Sync();
  }
  std::ofstream(dir_ / kJournalName, std::ios::app) << R"({"event":"action_sta)";  // crash
  const JournalContents c = ReadJournal(dir_);
  ASSERT_EQ(c.events.size(), 3u);
  EXPECT_EQ(c.events[2]["event"], "step_completed");
  EXPECT_EQ(c.torn_lines, 1);
}

TEST_F(JournalTest, ABadCompleteLineNamesTheLine) {
  std::ofstream(dir_ / kJournalName) << "{\"event\":\"run_started\",\"t_s\":0}\n[1,2]\n";
  try {
    ReadJournal(dir_);
    FAIL();
  } catch (const JournalError& e) {
    EXPECT_THAT(e.what(), HasSubstr("journal.jsonl:2"));
  }
}

// Steps complete in order; the first one without step_completed is where a resume starts, and its
// first action's start is where its repeated rows begin.
TEST(ResumePoint, FirstIncompleteStepAndWhenItBegan) {
  JournalContents j;
  j.events = {{{"event", "run_started"}, {"t_s", 0.5}},
              {{"event", "action_started"}, {"t_s", 1.0}, {"step", 0}, {"index", 0}},
              {{"event", "step_completed"}, {"t_s", 5.0}, {"step", 0}},
              {{"event", "action_started"}, {"t_s", 5.5}, {"step", 1}, {"index", 1}},
              {{"event", "action_completed"}, {"t_s", 7.0}, {"step", 1}, {"index", 1}},
              {{"event", "action_started"}, {"t_s", 7.5}, {"step", 1}, {"index", 2}}};
  const ResumePoint p = FindResumePoint(j, 3);
  EXPECT_EQ(p.first_incomplete_step, 1u);
  ASSERT_TRUE(p.interrupted_step_started_s.has_value());
  EXPECT_EQ(*p.interrupted_step_started_s, 5.5);
  EXPECT_EQ(p.last_t_s, 7.5);
  EXPECT_FALSE(p.run_completed);
}

// A corrupt journal is refused by event, never trusted: a time of 1e308 once set the resumed
// clock so far ahead that the resume waited forever; step -1 was silently ignored.
TEST(ResumePoint, RefusesImpossibleTimesAndSteps) {
  const auto error_of = [](const nlohmann::json& bad) {
    JournalContents j;
    j.events = {{{"event", "run_started"}, {"t_s", 0.5}},
                {{"event", "step_completed"}, {"t_s", 2.0}, {"step", 0}},
                bad};
    try {
      FindResumePoint(j, 3);
    } catch (const JournalError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(
      error_of({{"event", "step_completed"}, {"step", 1}, {"t_s", 1e308}}),
      AllOf(HasSubstr("journal event 3 (step_completed)"), HasSubstr("not a time of a run")));
  EXPECT_THAT(error_of({{"event", "step_completed"}, {"step", -1}, {"t_s", 3.0}}),
              AllOf(HasSubstr("journal event 3"),
                    HasSubstr("\"step\" -1 is not a step of the sequence (0 ... 2)")));
  EXPECT_THAT(error_of({{"event", "action_started"}, {"step", 1.5}, {"t_s", 3.0}}),
              HasSubstr("\"step\" 1.5"));
  EXPECT_THAT(error_of({{"event", "step_completed"}, {"step", 1}, {"t_s", 1.0}}),
              HasSubstr("before the previous"));
  EXPECT_EQ(error_of({{"event", "step_completed"}, {"step", 1}, {"t_s", 3.0}}), "accepted");
}

TEST(ResumePoint, RefusesAJournalWithoutRunStarted) {
  JournalContents j;
  j.events = {{{"event", "step_completed"}, {"t_s", 5.0}, {"step", 0}}};
  EXPECT_THROW(FindResumePoint(j, 2), JournalError);
}

}  // namespace
}  // namespace adahrs::calib
