// The serial line of one instrument role as its driver uses it: opened from the station entry,
// with the entry's reply timeout and bounded retries, and every failure turned into an
// InstrumentError naming the role, the port, the command and what came back.
// Timeouts: the station's `timeout_ms` is clock time (the instrument's own reply delay runs on the
// rig's simulated clock); the wall-clock wait is that divided by the time scale, never below
// kMinWallReplyTimeout, so that the PC's own scheduling cannot make a fast rig look silent.
// Used by the line-oriented drivers (ATL, Watlow 942, Prologix); Modbus has libmodbus's own port.
// Left out: reopening a port that disappeared (a USB adapter unplugged): that stops the run.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hil/clock.h"
#include "hil/instruments/instrument_error.h"
#include "hil/station.h"
#include "hil/transport/serial_port.h"

namespace adahrs::hil {

/// Floor of one reply's wall-clock wait, whatever the time scale. A busy PC (a loaded build
/// machine, the two benches of a demo and the rig sharing two cores) can leave a reading thread
/// unscheduled for a few hundred milliseconds; below a second the floor buys nothing but false
/// "no reply" verdicts, and it costs only when an instrument really is silent.
inline constexpr std::chrono::milliseconds kMinWallReplyTimeout{1000};

/// Floor of the wall-clock silence that DrainUntilQuiet takes for a quiet line: a rig or an
/// instrument adapter still sending can be unscheduled for tens of milliseconds on a busy PC.
inline constexpr std::chrono::milliseconds kMinWallQuiet{100};

/// The wall-clock wait for a reply promised within `timeout_ms` of clock time.
std::chrono::milliseconds WallReplyTimeout(const Clock& clock, int timeout_ms);

class InstrumentPort {
 public:
  /// Opens the entry's port; throws InstrumentError kNoReply (command "open") if it cannot.
  InstrumentPort(const InstrumentEntry& entry, const Clock& clock);

  const InstrumentEntry& entry() const { return entry_; }
  SerialPort& port() { return *port_; }
  std::chrono::milliseconds reply_timeout() const {
    return WallReplyTimeout(clock_, entry_.timeout_ms);
  }

  /// Writes `request`; throws kNoReply naming `command` if the write cannot complete.
  void Send(const std::string& command, std::string_view request);

  /// Sends `request` (input discarded first) and returns what arrives up to and including
  /// `terminator`; an attempt that times out is repeated, up to the entry's `retries` times, then
  /// throws kNoReply with whatever partial reply arrived.
  std::string Exchange(const std::string& command,
                       std::string_view request,
                       std::string_view terminator);

  /// Exchange that reads on past replies `is_answer` rejects (each ending in `terminator`), for
  /// a request that makes the instrument answer something else first (a line end that ends a
  /// stale partial line). Returns every reply read, the accepted one last; when the wait ends
  /// with replies but none accepted, returns them (the caller judges the last). Retries and
  /// kNoReply as Exchange.
  std::vector<std::string> ExchangeUntil(const std::string& command,
                                         std::string_view request,
                                         std::string_view terminator,
                                         const std::function<bool(std::string_view)>& is_answer);

  /// Reads and drops what arrives until nothing has arrived for `quiet_s` of clock time (and
  /// kMinWallQuiet of wall time), or until one reply timeout has passed on a line that never
  /// falls quiet. For a first command after a stranger used the line (a station with swapped
  /// ports): the instrument may still be answering that client's commands after it closed, and
  /// the tail of such an answer would read as the reply to ours. Returns the bytes dropped.
  size_t DrainUntilQuiet(const std::string& command, double quiet_s);

  [[noreturn]] void Fail(InstrumentError::Kind kind,
                         const std::string& command,
                         const std::string& reply,
                         const std::string& detail) const;

 private:
  InstrumentEntry entry_;
  const Clock& clock_;
  std::unique_ptr<SerialPort> port_;
};

}  // namespace adahrs::hil
