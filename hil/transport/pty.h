// A pseudo-terminal pair (POSIX posix_openpt): the rig serves a device on the master side; any
// serial client (our drivers through Boost.Asio's serial_port, pyserial, mbpoll, socat) opens the
// slave path as it would open /dev/ttyUSB0.
//
// The slave is put in raw mode (cfmakeraw: 8 data bits, no echo, no line editing, no CR/LF
// translation) so bytes pass unchanged. The pair keeps its own slave descriptor open so the master
// never sees EIO between client sessions; as on a real line, bytes written while no client reads
// are lost once the kernel buffer is full (the master is non-blocking and write() reports it).
// Left out: baud-rate pacing (a pty moves bytes at memory speed; devices pace their own replies on
// the simulated clock), modem control lines, parity errors.
#pragma once

#include <cstddef>
#include <string>

namespace adahrs::hil {

class PtyPair {
 public:
  /// Opens a new pair; throws std::system_error naming the failing call.
  static PtyPair Open();

  PtyPair(PtyPair&& other) noexcept;
  PtyPair& operator=(PtyPair&& other) noexcept;
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;
  ~PtyPair();

  /// Non-blocking master descriptor (the device side).
  int master_fd() const { return master_fd_; }
  /// Path of the slave device (the client side), e.g. /dev/pts/7.
  const std::string& slave_path() const { return slave_path_; }
  /// The pair's own slave descriptor (kept open so the master never reads EIO): not a client.
  int slave_fd() const { return slave_fd_; }
  /// Bytes written on the master that no client has read yet (FIONREAD on the pair's own slave
  /// descriptor: the slave's input queue, which every client of the path shares).
  size_t UnreadBytes() const;

 private:
  PtyPair(int master_fd, int slave_fd, std::string slave_path);
  void Close();

  int master_fd_ = -1;
  int slave_fd_ = -1;
  std::string slave_path_;
};

}  // namespace adahrs::hil
