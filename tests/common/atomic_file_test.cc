// WriteFileAtomically: the new text arrives whole, and every failure (a write cut short by the
// file size limit, a directory in the way, a directory that refuses new files) leaves the old file
// as it was, no temporary behind, and an error that names the file.
#include "common/atomic_file.h"

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace adahrs::common {
namespace {

using ::testing::HasSubstr;

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void WriteByHand(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("adahrs_atomic_file_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::filesystem::permissions(dir_, std::filesystem::perms::owner_all);
    std::filesystem::remove_all(dir_);
  }
  // The error WriteFileAtomically throws for `path` (the test fails if it throws none).
  std::string FailureOf(const std::filesystem::path& path, const std::string& text) {
    try {
      WriteFileAtomically(path, text);
    } catch (const AtomicWriteError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no error writing " << path;
    return "";
  }
  std::filesystem::path dir_;
};

TEST_F(AtomicFile, WritesEveryByteAndLeavesNoTemporary) {
  const std::string text = std::string("line 1\n\0binary\xff\n", 16) + std::string(300000, 'x');
  WriteFileAtomically(dir_ / "a.json", text);
  EXPECT_EQ(ReadAll(dir_ / "a.json"), text);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "a.json.tmp"));
}

TEST_F(AtomicFile, ReplacesTheOldFileAndAStaleTemporary) {
  WriteByHand(dir_ / "a.json", "old text, longer than the new one");
  WriteByHand(dir_ / "a.json.tmp", "left by a crash");
  WriteFileAtomically(dir_ / "a.json", "new");
  EXPECT_EQ(ReadAll(dir_ / "a.json"), "new");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "a.json.tmp"));
}

TEST_F(AtomicFile, AWriteCutShortLeavesTheOldFile) {
  WriteByHand(dir_ / "a.json", "old");
  // A file size limit of 4 KiB: writing 64 KiB fails part way with EFBIG (SIGXFSZ ignored).
  rlimit saved{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = saved;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string error = FailureOf(dir_ / "a.json", std::string(65536, 'n'));
  ::setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_THAT(error, HasSubstr((dir_ / "a.json").string() + ": cannot write the temporary"));
  EXPECT_THAT(error, HasSubstr("File too large"));
  EXPECT_EQ(ReadAll(dir_ / "a.json"), "old");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "a.json.tmp"));
}

TEST_F(AtomicFile, ADirectoryInTheWayIsLeftAsItWas) {
  std::filesystem::create_directories(dir_ / "report.html");
  WriteByHand(dir_ / "report.html" / "inside", "kept");
  const std::string error = FailureOf(dir_ / "report.html", "<html/>");
  EXPECT_THAT(error, HasSubstr((dir_ / "report.html").string() + ": cannot rename"));
  EXPECT_TRUE(std::filesystem::is_directory(dir_ / "report.html"));
  EXPECT_EQ(ReadAll(dir_ / "report.html" / "inside"), "kept");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "report.html.tmp"));
}

TEST_F(AtomicFile, AMissingDirectoryIsNamed) {
  const std::string error = FailureOf(dir_ / "no_such_dir" / "a.json", "x");
  EXPECT_THAT(error, HasSubstr((dir_ / "no_such_dir" / "a.json").string()));
  EXPECT_THAT(error, HasSubstr("No such file or directory"));
}

// Root writes into a read-only directory, so as root the attempt is made by a child process
// that has become `nobody` (uid and gid 65534); the error comes back through a pipe.
std::string FailureAsUnprivileged(const std::filesystem::path& path, const std::string& text) {
  int fds[2];
  if (::pipe(fds) != 0) return "pipe failed";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    std::string message = "no error";
    if (::setgid(65534) != 0 || ::setuid(65534) != 0) {
      message = "cannot become nobody";
    } else {
      try {
        WriteFileAtomically(path, text);
      } catch (const AtomicWriteError& e) {
        message = e.what();
      }
    }
    const ssize_t written = ::write(fds[1], message.data(), message.size());
    ::_exit(written == static_cast<ssize_t>(message.size()) ? 0 : 1);
  }
  ::close(fds[1]);
  std::string message;
  char buffer[512];
  for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) > 0;) message.append(buffer, n);
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return message;
}

TEST_F(AtomicFile, ADirectoryThatRefusesNewFilesLeavesTheOldFile) {
  WriteByHand(dir_ / "a.json", "old");
  namespace fs = std::filesystem;
  fs::permissions(dir_,
                  fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                      fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  const std::string error = ::geteuid() == 0 ? FailureAsUnprivileged(dir_ / "a.json", "new")
                                             : FailureOf(dir_ / "a.json", "new");
  EXPECT_THAT(error, HasSubstr((dir_ / "a.json").string() + ": cannot create the temporary"));
  EXPECT_THAT(error, HasSubstr("Permission denied"));
  EXPECT_EQ(ReadAll(dir_ / "a.json"), "old");
  EXPECT_FALSE(fs::exists(dir_ / "a.json.tmp"));
}

}  // namespace
}  // namespace adahrs::common
