// RunChildProgram against real programs (cat, sh, sleep, pwd): what they read, print, exit with
// and how long they run, bounded by the timeout on a loaded machine.
#include "common/child_program.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

namespace adahrs::common {
namespace {

using ::testing::HasSubstr;

ChildProgramResult Spawn(std::vector<std::string> argv,
                         std::string in = "",
                         double timeout_s = 60.0,
                         std::filesystem::path dir = {}) {
  return RunChildProgram({std::move(argv), std::move(dir), std::move(in), timeout_s});
}

TEST(ChildProgram, PassesEightMegabytesThroughCatUnchanged) {
  std::string in;
  for (int64_t i = 0; in.size() < (8u << 20); ++i) in += std::to_string(i * 7919) + "\n";
  const ChildProgramResult r = Spawn({"cat"}, in);
  EXPECT_TRUE(r.Succeeded()) << r.Outcome(60);
  EXPECT_TRUE(r.stdin_fully_read);
  EXPECT_EQ(r.stdout_bytes, in);
  EXPECT_EQ(r.stderr_tail, "");
}

TEST(ChildProgram, ReportsExitStatusAndStderr) {
  const ChildProgramResult r = Spawn({"sh", "-c", "echo half >&2; printf '{\"a\":'; exit 3"});
  EXPECT_FALSE(r.Succeeded());
  ASSERT_TRUE(r.exit_status.has_value());
  EXPECT_EQ(*r.exit_status, 3);
  EXPECT_EQ(r.stderr_tail, "half\n");
  EXPECT_EQ(r.stdout_bytes, "{\"a\":");
  EXPECT_EQ(r.Outcome(60), "exit status 3");
}

TEST(ChildProgram, ReportsTheSignalThatEndedIt) {
  const ChildProgramResult r = Spawn({"sh", "-c", "kill -TERM $$"});
  EXPECT_FALSE(r.Succeeded());
  ASSERT_TRUE(r.signal.has_value());
  EXPECT_EQ(*r.signal, 15);
  EXPECT_THAT(r.Outcome(60), HasSubstr("signal 15"));
}

TEST(ChildProgram, KillsItAndWhatItStartedAtTheTimeout) {
  // The background sleep holds stdout open: only a kill of the process group ends the wait.
  const ChildProgramResult r = Spawn({"sh", "-c", "sleep 120 & sleep 120"}, "", 0.5);
  EXPECT_TRUE(r.timed_out);
  EXPECT_FALSE(r.Succeeded());
  EXPECT_LT(r.elapsed_s, 30.0);  // 0.5 s asked; a loaded machine adds scheduling, not minutes
  EXPECT_EQ(r.Outcome(0.5), "did not finish in 0 s and was killed");
}

TEST(ChildProgram, SaysWhyAProgramDidNotStart) {
  const ChildProgramResult missing = Spawn({"adahrs-no-such-program-here"});
  EXPECT_FALSE(missing.Succeeded());
  EXPECT_THAT(missing.start_error, HasSubstr("No such file or directory"));
  const ChildProgramResult no_dir = Spawn({"pwd"}, "", 60, "/nonexistent-adahrs-dir");
  EXPECT_THAT(no_dir.start_error, HasSubstr("working directory /nonexistent-adahrs-dir"));
  EXPECT_EQ(Spawn({}).start_error, "no program named");
}

TEST(ChildProgram, RunsInTheWorkingDirectoryGiven) {
  const ChildProgramResult r = Spawn({"pwd"}, "", 60, "/usr/share");
  EXPECT_TRUE(r.Succeeded());
  EXPECT_EQ(r.stdout_bytes, "/usr/share\n");
}

TEST(ChildProgram, NoticesAProgramThatExitsWithoutReadingItsInput) {
  const ChildProgramResult r = Spawn({"sh", "-c", "echo done"}, std::string(4u << 20, 'x'));
  EXPECT_TRUE(r.Succeeded());
  EXPECT_FALSE(r.stdin_fully_read);
  EXPECT_EQ(r.stdout_bytes, "done\n");
  // A request small enough to wait whole in the pipe, never read.
  EXPECT_FALSE(Spawn({"sh", "-c", "sleep 0.2"}, "{\"a\": 1}\n").stdin_fully_read);
  // Read up to the object's end, the final newline left: read.
  EXPECT_TRUE(Spawn({"sh", "-c", "head -c 8 >/dev/null"}, "{\"a\": 1}\n \n").stdin_fully_read);
  EXPECT_FALSE(Spawn({"sh", "-c", "head -c 7 >/dev/null"}, "{\"a\": 1}\n").stdin_fully_read);
}

}  // namespace
}  // namespace adahrs::common
