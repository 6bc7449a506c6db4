// Test helper: a serial client on a pty slave path, as any outside program would open it.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace adahrs::rig_sim::testing {

class PtyClient {
 public:
  explicit PtyClient(const std::string& path) : fd_(::open(path.c_str(), O_RDWR | O_NOCTTY)) {
    if (fd_ < 0) throw std::runtime_error("cannot open " + path);
    termios tio{};
    ::tcgetattr(fd_, &tio);
    ::cfmakeraw(&tio);
    ::tcsetattr(fd_, TCSANOW, &tio);
  }
  ~PtyClient() { ::close(fd_); }
  PtyClient(const PtyClient&) = delete;
  PtyClient& operator=(const PtyClient&) = delete;

  void Write(const std::vector<uint8_t>& bytes) {
    if (::write(fd_, bytes.data(), bytes.size()) != static_cast<ssize_t>(bytes.size())) {
      throw std::runtime_error("short write");
    }
  }
  void WriteText(const std::string& text) { Write({text.begin(), text.end()}); }

  /// Appends to `out` whatever arrives within `wall_s`.
  void ReadFor(double wall_s, std::vector<uint8_t>& out) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(wall_s);
    while (std::chrono::steady_clock::now() < end) ReadSome(out, 5);
  }

  /// Reads until `out` holds at least `count` bytes or `timeout_s` passes; true if it does.
  bool ReadAtLeast(size_t count, double timeout_s, std::vector<uint8_t>& out) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (out.size() < count && std::chrono::steady_clock::now() < end) ReadSome(out, 5);
    return out.size() >= count;
  }

  /// One line (without the newline) or "<timeout>".
  std::string ReadLine(double timeout_s) {
    std::vector<uint8_t> bytes;
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 5) <= 0) continue;
      uint8_t c;
      if (::read(fd_, &c, 1) != 1) continue;
      if (c == '\n') return {bytes.begin(), bytes.end()};
      bytes.push_back(c);
    }
    return "<timeout>";
  }

  /// Sends a control command and returns its reply line.
  std::string Command(const std::string& line) {
    WriteText(line + "\n");
    return ReadLine(5.0);
  }

  int fd() const { return fd_; }

  /// Discards whatever is waiting.
  void Drain() { ::tcflush(fd_, TCIFLUSH); }

 private:
  void ReadSome(std::vector<uint8_t>& out, int timeout_ms) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, timeout_ms) <= 0) return;
    uint8_t buffer[65536];
    const ssize_t n = ::read(fd_, buffer, sizeof buffer);
    if (n > 0) out.insert(out.end(), buffer, buffer + n);
  }

  int fd_;
};

}  // namespace adahrs::rig_sim::testing
