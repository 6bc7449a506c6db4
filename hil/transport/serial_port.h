// A serial port client on Boost.Asio (`serial_port`), the one transport every instrument driver
// and unit driver uses: a real /dev/ttyUSB0 on the production PC and a pty slave of the virtual rig
// are opened the same way. Synchronous calls with timeouts (an internal io_context runs each
// operation for at most its timeout, then cancels it). Every byte moved can be traced (the frame
// trace switch of STYLE.md §8.6, like libmodbus's modbus_set_debug).
// Errors are TransportError naming the instrument role, the port and what failed.
// Left out: modem control lines, break signalling, RS-485 direction control.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace adahrs::hil {

class TransportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Thrown when an operation's timeout expires; what() names the instrument, port and operation.
class TransportTimeout : public TransportError {
 public:
  using TransportError::TransportError;
};

struct SerialSettings {
  std::string path;
  unsigned baud = 9600;
  unsigned data_bits = 8;
  char parity = 'N';  ///< 'N', 'E' or 'O'
  unsigned stop_bits = 1;
  enum class Flow { kNone, kSoftware, kHardware } flow = Flow::kNone;
};

/// Whether the port is taken for this client alone: an exclusive open holds flock(LOCK_EX) on the
/// device for its lifetime (what pyserial's `exclusive=True` takes), so a second pipeline, or a
/// second open of the same device by another path, is refused instead of splitting the replies.
/// Shared is for a line made to be shared (the virtual rig's control port).
enum class PortAccess { kExclusive, kShared };

enum class TraceDirection { kSent, kReceived };
using TraceSink = std::function<void(TraceDirection, std::span<const uint8_t>)>;

class SerialPort {
 public:
  /// Opens and configures the port; discards bytes that arrived before it was opened. Throws
  /// TransportError when an exclusive open finds the port held by another open.
  SerialPort(const SerialSettings& settings,
             std::string role,
             PortAccess access = PortAccess::kExclusive);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  /// Writes all of `bytes` within `timeout`.
  void Write(std::span<const uint8_t> bytes, std::chrono::milliseconds timeout);
  void Write(std::string_view text, std::chrono::milliseconds timeout);

  /// Reads what is available, waiting up to `timeout` for the first byte; returns 0 bytes on
  /// timeout (not an error: a poll).
  size_t ReadSome(std::span<uint8_t> buffer, std::chrono::milliseconds timeout);

  /// Reads until `terminator` has been received (returned text includes it); throws
  /// TransportTimeout with what did arrive when `timeout` expires first.
  std::string ReadUntil(std::string_view terminator, std::chrono::milliseconds timeout);

  /// Reads exactly `count` bytes or throws TransportTimeout.
  std::vector<uint8_t> ReadExactly(size_t count, std::chrono::milliseconds timeout);

  /// Drops bytes received but not read yet. With software flow control the bytes are read and
  /// dropped rather than flushed: tcflush(TCIFLUSH) also discards bytes the line discipline has
  /// not processed yet, and an instrument's XON among them would leave output stopped for good
  /// (the next write times out; seen with the Watlow 942, docs/rig/watlow-942.md).
  void DiscardInput();

  /// Every byte sent and received is passed to `sink` (nullptr switches tracing off).
  void SetTrace(TraceSink sink) { trace_ = std::move(sink); }

  const std::string& role() const { return role_; }
  const std::string& path() const { return path_; }

 private:
  std::string Describe(const std::string& what) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string role_;
  std::string path_;
  SerialSettings::Flow flow_;
  std::vector<uint8_t> pending_;  // received beyond a terminator, kept for the next read
  TraceSink trace_;
};

/// Formats bytes as hex, e.g. for traces and error messages ("01 03 00 64").
std::string HexBytes(std::span<const uint8_t> bytes, size_t max_bytes = 64);

}  // namespace adahrs::hil
