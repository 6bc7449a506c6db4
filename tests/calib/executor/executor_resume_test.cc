// Crash and resume: `adahrs run` as a child process is killed with SIGKILL in the middle of a
// step, then `adahrs run --resume` finishes the run. Expected: every complete gzip member of
// imu.csv.gz at the kill is still there byte for byte, a torn one is set aside and journaled
// (planted when the kill falls between two members), the interrupted step is repeated and its
// first attempt marked as a rejected interval, and the calibration rows per unit per acquisition
// are complete (N each).
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>
#include <zlib.h>

#include "calib/executor/journal.h"
#include "hil/recording/gzip_reader.h"
#include "tests/calib/executor/executor_test_util.h"

extern char** environ;

namespace adahrs::calib {
namespace {

using testing::TempDir;

pid_t Spawn(std::vector<std::string> args, const std::filesystem::path& log) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(
      &actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + args[0]);
  return pid;
}

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The compressed bytes of `gz` up to the end of its last complete member, and their text.
std::pair<std::string, std::string> CompleteMembers(const std::filesystem::path& gz,
                                                    const std::filesystem::path& scratch) {
  size_t complete_bytes = 0;
  {
    hil::GzipReader reader(gz);
    std::vector<char> block(1 << 16);
    while (reader.Read(block.data(), block.size()) > 0) {
    }
    complete_bytes = reader.complete_bytes();
  }
  const std::string compressed = ReadAll(gz).substr(0, complete_bytes);
  std::ofstream(scratch, std::ios::binary) << compressed;
  hil::GzipReader reader(scratch);
  std::string text;
  std::vector<char> block(1 << 16);
  for (size_t n; (n = reader.Read(block.data(), block.size())) > 0;) text.append(block.data(), n);
  return {compressed, text};
}

// `text` as one gzip member, as the recording writer appends them.
std::string GzipMember(const std::string& text) {
  z_stream z{};
  if (deflateInit2(&z, 1, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("deflateInit2");
  std::string out(deflateBound(&z, text.size()) + 32, '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  z.avail_in = static_cast<uInt>(text.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  if (rc != Z_STREAM_END) throw std::runtime_error("deflate");
  return out;
}

bool JournalHasStepCompleted(const std::filesystem::path& run_dir, int step) {
  if (!std::filesystem::exists(run_dir / kJournalName)) return false;
  for (const auto& e : ReadJournal(run_dir).events) {
    const auto* completed = std::get_if<StepCompleted>(&e);
    if (completed != nullptr && completed->step == static_cast<size_t>(step)) return true;
  }
  return false;
}

TEST(ExecutorResume, KilledRunResumesWithEveryRowKeptAndTheRepeatedStepMarked) {
  // 100x: the kill lands inside step 2 (mount, interlock, 3 s of packets: ~6 s, 60 ms wall).
  adahrs::testing::RigProcess rig(100.0);
  TempDir dir("resume");
  const std::string station = rig.WriteStation();
  const std::string sequence = testing::WriteSequence(dir.path(), "imu", nlohmann::json::parse(R"([
    {"kind": "accel", "orientation": 11, "packets": 300},
    {"kind": "accel", "orientation": 12, "packets": 300},
    {"kind": "accel", "orientation": 21, "packets": 300},
    {"kind": "accel", "orientation": 22, "packets": 300}])"));
  const std::filesystem::path run_dir = dir.path() / "run";
  const std::string adahrs = std::string(std::getenv("ADAHRS_BIN_DIR")) + "/adahrs";
  const pid_t first = Spawn(
      {adahrs, "run", "--station", station, "--sequence", sequence, "--run-dir", run_dir.string()},
      dir.path() / "first.log");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!JournalHasStepCompleted(run_dir, 1) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  ::kill(first, SIGKILL);
  int status = 0;
  ::waitpid(first, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << ReadAll(dir.path() / "first.log");
  std::string imu_at_kill = ReadAll(run_dir / "imu.csv.gz");
  const auto [complete_at_kill, text_at_kill] =
      CompleteMembers(run_dir / "imu.csv.gz", dir.path() / "members.gz");
  ASSERT_FALSE(text_at_kill.empty());
  ASSERT_FALSE(JournalHasStepCompleted(run_dir, 2)) << "killed too late to test a partial step";
  // The kill lands inside a member's write or between two. Between two it leaves no torn tail, so
  // one is planted as a write cut short leaves it: the first half of a member of the last rows.
  // Either way the resume below must set a torn member aside.
  const bool torn_by_kill = complete_at_kill.size() != imu_at_kill.size();
  if (!torn_by_kill) {
    const size_t last_rows = text_at_kill.rfind('\n', text_at_kill.size() - 2);
    const size_t from = text_at_kill.rfind('\n', last_rows - 1) + 1;
    const std::string member = GzipMember(text_at_kill.substr(from));
    const std::string torn = member.substr(0, member.size() / 2);
    std::ofstream(run_dir / "imu.csv.gz", std::ios::binary | std::ios::app) << torn;
    imu_at_kill += torn;
  }
  std::printf("the kill %s\n",
              torn_by_kill ? "tore a gzip member" : "fell between members: a torn one planted");

  // A restart takes a moment; an instrument reply to the killed process's last request lands in
  // the pty meanwhile and the new process's port open discards it. (Without the pause the Watlow
  // F4 driver may read that stale reply as its own and fail with "Invalid data" rather than
  // retry: reported to the drivers owner.)
  std::this_thread::sleep_for(std::chrono::milliseconds(200));

  // A copy whose last complete row is garbled is refused by file and line before anything moves
  // (it died with a bare "stod"); the copy's rows are plain text, as `adahrs run --plain-csv`
  // writes them, and resume reads them in that form.
  const std::filesystem::path garbled = dir.path() / "garbled";
  std::filesystem::copy(run_dir, garbled, std::filesystem::copy_options::recursive);
  std::filesystem::remove(garbled / "imu.csv.gz");
  const size_t last_row = text_at_kill.rfind('\n', text_at_kill.size() - 2) + 1;
  std::ofstream(garbled / "imu.csv", std::ios::binary)
      << text_at_kill.substr(0, last_row) << "x" << text_at_kill.substr(last_row);
  const long last_line =
      static_cast<long>(std::count(text_at_kill.begin(), text_at_kill.end(), '\n'));
  const pid_t refused =
      Spawn({adahrs, "run", "--resume", garbled.string()}, dir.path() / "garbled.log");
  ::waitpid(refused, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) != 0);
  EXPECT_NE(ReadAll(dir.path() / "garbled.log")
                .find("imu.csv:" + std::to_string(last_line) + ": column 1 (t_s) 'x"),
            std::string::npos)
      << ReadAll(dir.path() / "garbled.log");

  const pid_t second =
      Spawn({adahrs, "run", "--resume", run_dir.string()}, dir.path() / "second.log");
  ::waitpid(second, &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << ReadAll(dir.path() / "second.log");

  // Nothing logged before the kill is lost: the file still starts with every complete member.
  const std::string imu_after = ReadAll(run_dir / "imu.csv.gz");
  EXPECT_EQ(imu_after.compare(0, complete_at_kill.size(), complete_at_kill), 0);
  // The torn member was set aside byte for byte, and journaled.
  ASSERT_GT(imu_at_kill.size(), complete_at_kill.size());
  EXPECT_EQ(ReadAll(run_dir / "imu.csv.gz.torn-1"), imu_at_kill.substr(complete_at_kill.size()));
  bool torn_journaled = false;
  for (const auto& e : ReadJournal(run_dir).events) {
    const auto* torn = std::get_if<TornTailSetAside>(&e);
    torn_journaled |= torn != nullptr && torn->file == "imu.csv.gz";
  }
  EXPECT_TRUE(torn_journaled);

  const hil::Recording rec = hil::ReadRecording(run_dir);
  EXPECT_EQ(rec.meta.status.value_or(""), "complete");
  ASSERT_EQ(rec.meta.rejected_intervals.size(), 1u);
  EXPECT_EQ(rec.meta.rejected_intervals[0].step, 2);
  EXPECT_EQ(rec.meta.rejected_intervals[0].reason, "repeated partial step");
  bool repeat_journaled = false;
  for (const auto& e : ReadJournal(run_dir).events)
    repeat_journaled |= std::holds_alternative<StepRepeated>(e);
  EXPECT_TRUE(repeat_journaled);
  // Time keeps increasing across the resume.
  for (size_t i = 1; i < rec.imu.size(); ++i) {
    if (rec.imu[i].unit != rec.imu[i - 1].unit) continue;
    ASSERT_GE(rec.imu[i].t_s, rec.imu[i - 1].t_s) << i;
  }
  const auto tagged = testing::TaggedImuRows(rec);
  for (int u = 1; u <= 4; ++u) {
    const std::string serial = "IMU-000" + std::to_string(u);
    for (int tag = 1; tag <= 4; ++tag) {
      const auto it = tagged.find({serial, tag});
      ASSERT_NE(it, tagged.end()) << serial << " tag " << tag;
      EXPECT_EQ(it->second.size(), 300u) << serial << " tag " << tag;
    }
  }
}

}  // namespace
}  // namespace adahrs::calib
