#include "hil/transport/pty.h"

#include <fcntl.h>
#include <stdlib.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>
#include <utility>

namespace adahrs::hil {
namespace {

[[noreturn]] void ThrowErrno(const std::string& what) {
  throw std::system_error(errno, std::generic_category(), "pty: " + what);
}

}  // namespace

PtyPair PtyPair::Open() {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (master < 0) ThrowErrno("posix_openpt");
  if (::grantpt(master) != 0 || ::unlockpt(master) != 0) {
    const int saved = errno;
    ::close(master);
    errno = saved;
    ThrowErrno("grantpt/unlockpt");
  }
  char name[128];
  if (::ptsname_r(master, name, sizeof name) != 0) {
    const int saved = errno;
    ::close(master);
    errno = saved;
    ThrowErrno("ptsname_r");
  }
  const int slave = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (slave < 0) {
    const int saved = errno;
    ::close(master);
    errno = saved;
    ThrowErrno(std::string("open ") + name);
  }
  termios tio{};
  if (::tcgetattr(slave, &tio) == 0) {
    ::cfmakeraw(&tio);
    ::tcsetattr(slave, TCSANOW, &tio);
  }
  return PtyPair(master, slave, name);
}

PtyPair::PtyPair(int master_fd, int slave_fd, std::string slave_path)
    : master_fd_(master_fd), slave_fd_(slave_fd), slave_path_(std::move(slave_path)) {}

PtyPair::PtyPair(PtyPair&& other) noexcept
    : master_fd_(std::exchange(other.master_fd_, -1)),
      slave_fd_(std::exchange(other.slave_fd_, -1)),
      slave_path_(std::move(other.slave_path_)) {}

PtyPair& PtyPair::operator=(PtyPair&& other) noexcept {
  if (this != &other) {
    Close();
    master_fd_ = std::exchange(other.master_fd_, -1);
    slave_fd_ = std::exchange(other.slave_fd_, -1);
    slave_path_ = std::move(other.slave_path_);
  }
  return *this;
}

PtyPair::~PtyPair() { Close(); }

void PtyPair::Close() {
  if (slave_fd_ >= 0) ::close(slave_fd_);
  if (master_fd_ >= 0) ::close(master_fd_);
  slave_fd_ = master_fd_ = -1;
}

size_t PtyPair::UnreadBytes() const {
  int unread = 0;
  if (slave_fd_ < 0 || ::ioctl(slave_fd_, FIONREAD, &unread) != 0 || unread < 0) return 0;
  return static_cast<size_t>(unread);
}

}  // namespace adahrs::hil
