// Runs another program as a child process with its standard input given and its standard output
// and error captured: one request in, one reply out, bounded in time. The child gets its own
// process group, so a timeout kills what it started too. POSIX (posix_spawn, poll).
// Left out: a terminal, environment changes (the child inherits ours), output beyond
// kMaxChildStdoutBytes (the child is killed and the result says so).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace adahrs::common {

inline constexpr size_t kMaxChildStdoutBytes = size_t{1} << 30;  ///< 1 GiB
inline constexpr size_t kChildStderrTailBytes = 64 * 1024;       ///< the end of stderr kept

struct ChildProgramCall {
  std::vector<std::string> argv;            ///< argv[0] searched in PATH unless it holds a '/'
  std::filesystem::path working_directory;  ///< empty: ours
  std::string stdin_bytes;                  ///< written, then stdin is closed
  double timeout_s = 600.0;
};

struct ChildProgramResult {
  std::string start_error;         ///< non-empty: the program did not start (the system's reason)
  bool timed_out = false;          ///< killed at the timeout
  bool stdout_overflow = false;    ///< killed: stdout passed kMaxChildStdoutBytes
  std::optional<int> exit_status;  ///< the status it exited with
  std::optional<int> signal;       ///< the signal that ended it
  /// false: it ended with part of its stdin unread (a trailing white space aside)
  bool stdin_fully_read = true;
  std::string stdout_bytes;
  std::string stderr_tail;  ///< the last kChildStderrTailBytes of stderr
  double elapsed_s = 0.0;

  /// Started, exited by itself with status 0.
  bool Succeeded() const {
    return start_error.empty() && !timed_out && !stdout_overflow && exit_status &&
           *exit_status == 0;
  }
  /// What ended it, for a message: "exit status 3", "signal 9 (Killed)", "did not finish in 5 s".
  std::string Outcome(double timeout_s) const;
};

/// Runs the call to its end (or its timeout); throws nothing for the child's failures (they are
/// in the result), std::system_error when a pipe or poll fails.
ChildProgramResult RunChildProgram(const ChildProgramCall& call);

}  // namespace adahrs::common
