#include "common/child_program.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <system_error>
#include <thread>

extern char** environ;

namespace adahrs::common {
namespace {

using Clock = std::chrono::steady_clock;

[[noreturn]] void ThrowErrno(const char* what) {
  throw std::system_error(errno, std::generic_category(), what);
}

struct Pipe {
  int read = -1;
  int write = -1;
};

Pipe MakePipe() {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) ThrowErrno("pipe2");
  return {fds[0], fds[1]};
}

void Close(int* fd) {
  if (*fd >= 0) ::close(*fd);
  *fd = -1;
}

// Writes what the pipe takes now without a SIGPIPE for a reader that went away; returns the bytes
// written, or -1 when the reader closed its end.
ssize_t WriteSome(int fd, const char* data, size_t size) {
  sigset_t pipe_only, previous;
  sigemptyset(&pipe_only);
  sigaddset(&pipe_only, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_only, &previous);
  const ssize_t n = ::write(fd, data, size);
  const int saved = errno;
  if (n < 0 && saved == EPIPE) {
    const timespec zero{0, 0};
    while (sigtimedwait(&pipe_only, nullptr, &zero) > 0) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  errno = saved;
  if (n < 0 && saved == EPIPE) return -1;
  if (n < 0 && (saved == EAGAIN || saved == EINTR)) return 0;
  if (n < 0) ThrowErrno("write to the child's stdin");
  return n;
}

// Spawns the child with the pipes on its 0, 1 and 2, in its own process group and directory.
pid_t Spawn(const ChildProgramCall& call,
            const Pipe& in,
            const Pipe& out,
            const Pipe& err,
            std::string* error) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in.read, 0);
  posix_spawn_file_actions_adddup2(&actions, out.write, 1);
  posix_spawn_file_actions_adddup2(&actions, err.write, 2);
  if (!call.working_directory.empty()) {
    posix_spawn_file_actions_addchdir_np(&actions, call.working_directory.c_str());
  }
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t defaults, empty;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  sigaddset(&defaults, SIGHUP);
  sigemptyset(&empty);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setsigmask(&attr, &empty);
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawnattr_setflags(&attr,
                           POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
  std::vector<char*> argv;
  for (const std::string& a : call.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = ::posix_spawnp(&pid, argv[0], &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) {
    *error = std::strerror(rc);
    if (!call.working_directory.empty() && !std::filesystem::is_directory(call.working_directory)) {
      *error += " (working directory " + call.working_directory.string() + " does not exist)";
    }
    return -1;
  }
  return pid;
}

// Whether the pipe still holds anything but white space (a reader may leave a final newline).
bool LeftUnread(int read_fd) {
  ::fcntl(read_fd, F_SETFL, O_NONBLOCK);
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(read_fd, buffer, sizeof buffer);
    if (n <= 0) return false;
    for (ssize_t i = 0; i < n; ++i) {
      if (!std::isspace(static_cast<unsigned char>(buffer[i]))) return true;
    }
  }
}

void Record(int status, ChildProgramResult* r) {
  if (WIFEXITED(status)) r->exit_status = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r->signal = WTERMSIG(status);
}

}  // namespace

std::string ChildProgramResult::Outcome(double timeout_s) const {
  if (!start_error.empty()) return "did not start: " + start_error;
  if (timed_out)
    return "did not finish in " + std::to_string(static_cast<long>(timeout_s)) +
           " s and was killed";
  if (stdout_overflow) return "wrote more than 1 GiB on stdout and was killed";
  if (signal) return "ended by signal " + std::to_string(*signal) + " (" + strsignal(*signal) + ")";
  if (exit_status) return "exit status " + std::to_string(*exit_status);
  return "unknown outcome";
}

ChildProgramResult RunChildProgram(const ChildProgramCall& call) {
  ChildProgramResult r;
  if (call.argv.empty() || call.argv[0].empty()) {
    r.start_error = "no program named";
    return r;
  }
  const auto start = Clock::now();
  const auto deadline = start + std::chrono::duration<double>(call.timeout_s);
  Pipe in = MakePipe(), out = MakePipe(), err = MakePipe();
  const pid_t pid = Spawn(call, in, out, err, &r.start_error);
  // The parent keeps a read end of stdin: what the child left unread is still there at its exit.
  Close(&out.write);
  Close(&err.write);
  if (pid < 0) {
    Close(&in.read);
    Close(&in.write);
    Close(&out.read);
    Close(&err.read);
    return r;
  }
  ::fcntl(in.write, F_SETFL, O_NONBLOCK);
  size_t written = 0;
  if (call.stdin_bytes.empty()) Close(&in.write);
  char buffer[65536];
  bool killed = false;
  while (out.read >= 0 || err.read >= 0) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) {
      r.timed_out = true;
      break;
    }
    pollfd fds[3] = {{out.read, POLLIN, 0}, {err.read, POLLIN, 0}, {in.write, POLLOUT, 0}};
    const int n = ::poll(fds, 3, static_cast<int>(std::min<long>(left.count(), 1000)));
    if (n < 0 && errno != EINTR) ThrowErrno("poll on the child's pipes");
    if (n <= 0) continue;
    if (fds[2].revents & (POLLOUT | POLLERR | POLLHUP)) {
      const ssize_t w =
          WriteSome(in.write, call.stdin_bytes.data() + written, call.stdin_bytes.size() - written);
      if (w < 0) {
        r.stdin_fully_read = false;
        Close(&in.write);
      } else {
        written += static_cast<size_t>(w);
        if (written == call.stdin_bytes.size()) Close(&in.write);
      }
    }
    for (int k = 0; k < 2; ++k) {
      int* fd = k == 0 ? &out.read : &err.read;
      if (!(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t got = ::read(*fd, buffer, sizeof buffer);
      if (got < 0 && (errno == EINTR || errno == EAGAIN)) continue;
      if (got <= 0) {
        Close(fd);
        continue;
      }
      std::string& sink = k == 0 ? r.stdout_bytes : r.stderr_tail;
      sink.append(buffer, static_cast<size_t>(got));
      if (k == 1 && sink.size() > 2 * kChildStderrTailBytes) {
        sink.erase(0, sink.size() - kChildStderrTailBytes);
      }
    }
    if (r.stdout_bytes.size() > kMaxChildStdoutBytes) {
      r.stdout_overflow = true;
      break;
    }
  }
  if (in.write >= 0 && written < call.stdin_bytes.size() && !r.timed_out && !r.stdout_overflow) {
    r.stdin_fully_read = false;
  }
  Close(&in.write);
  int status = 0;
  for (;;) {
    if (r.timed_out || r.stdout_overflow) {
      ::kill(-pid, SIGKILL);
      killed = true;
    }
    const pid_t done = ::waitpid(pid, &status, killed ? 0 : WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) ThrowErrno("waitpid");
    if (Clock::now() >= deadline) {
      r.timed_out = true;
      continue;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  Close(&out.read);
  Close(&err.read);
  if (r.stdin_fully_read && LeftUnread(in.read)) r.stdin_fully_read = false;
  Close(&in.read);
  Record(status, &r);
  if (r.stderr_tail.size() > kChildStderrTailBytes) {
    r.stderr_tail.erase(0, r.stderr_tail.size() - kChildStderrTailBytes);
  }
  r.elapsed_s = std::chrono::duration<double>(Clock::now() - start).count();
  return r;
}

}  // namespace adahrs::common
