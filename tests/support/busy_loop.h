// Test helper: a CPU-bound process beside a test (`yes > /dev/null`, as an operator would start
// one), for assertions that must hold on a loaded machine. Killed and reaped by the destructor.
// Header-only; links nothing but POSIX.
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace adahrs::testing {

class BusyLoop {
 public:
  BusyLoop() : pid_(::fork()) {
    if (pid_ == 0) {
      ::execl("/bin/sh", "sh", "-c", "exec yes > /dev/null", static_cast<char*>(nullptr));
      ::_exit(127);
    }
  }
  ~BusyLoop() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  BusyLoop(const BusyLoop&) = delete;
  BusyLoop& operator=(const BusyLoop&) = delete;

 private:
  pid_t pid_;
};

}  // namespace adahrs::testing
