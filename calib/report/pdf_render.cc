#include "calib/report/pdf_render.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

extern char** environ;

namespace adahrs::calib {
namespace {

// Waits for `pid` up to `timeout_s`; kills it after. Returns the wait status, or -1 on timeout.
int WaitWithTimeout(pid_t pid, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (;;) {
    int status = 0;
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) return status;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

}  // namespace

void RenderPdf(const std::filesystem::path& html,
               const std::filesystem::path& pdf,
               double timeout_s) {
  const std::string page = std::filesystem::absolute(html).string();
  if (::access(kChromiumPath, X_OK) != 0) {
    throw PdfRenderError(
        fmt::format("{}: no PDF: {} is not installed (scripts/setup installs Debian's chromium)",
                    page,
                    kChromiumPath));
  }
  const std::filesystem::path profile =
      std::filesystem::temp_directory_path() / fmt::format("adahrs-chromium-{}", ::getpid());
  std::filesystem::remove_all(profile);
  std::filesystem::remove(pdf);
  std::vector<std::string> args = {kChromiumPath,
                                   "--headless",
                                   "--no-sandbox",
                                   "--disable-gpu",
                                   "--disable-quic",
                                   "--no-first-run",
                                   "--disable-background-networking",
                                   "--disable-component-update",
                                   "--disable-sync",
                                   "--no-pdf-header-footer",
                                   "--user-data-dir=" + profile.string(),
                                   "--print-to-pdf=" + std::filesystem::absolute(pdf).string(),
                                   "file://" + page};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  // Chromium's own chatter (and its complaints about the closed network) is not ours to print.
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int spawned = ::posix_spawn(&pid, kChromiumPath, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    throw PdfRenderError(fmt::format("{}: no PDF: {} did not start", page, kChromiumPath));
  }
  const int status = WaitWithTimeout(pid, timeout_s);
  std::filesystem::remove_all(profile);
  if (status == -1) {
    throw PdfRenderError(fmt::format(
        "{}: no PDF: {} did not finish within {:.0f} s", page, kChromiumPath, timeout_s));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !std::filesystem::exists(pdf) ||
      std::filesystem::file_size(pdf) == 0) {
    throw PdfRenderError(fmt::format("{}: no PDF: {} exited with status {} and wrote {}",
                                     page,
                                     kChromiumPath,
                                     WIFEXITED(status) ? WEXITSTATUS(status) : -1,
                                     std::filesystem::exists(pdf) ? "an empty file" : "nothing"));
  }
}

}  // namespace adahrs::calib
