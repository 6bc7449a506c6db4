// The transmit side of a UART on the simulated clock: bytes leave at the line rate, one character
// time each (10 bit times for 8N1), behind a transmit buffer of fixed size.
//
// A frame queued at time t starts when the line is free (at t, or when the previous byte ends)
// and each byte is released to the client when its stop bit has left, so the client sees exactly
// the bytes a real line would have delivered by any simulated instant, whatever the granularity
// of the calls. A frame that does not fit the bytes still waiting in the transmit buffer is refused
// whole (firmware drops the packet rather than send part of it); the caller counts it.
// Left out: parity and stop-bit variants other than 8N1, inter-character gaps of a busy firmware,
// baud-rate error between the two ends.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <vector>

namespace adahrs::rig_sim {

class PacedLine {
 public:
  /// `baud` in 300…4,000,000 bits/s (8N1: 10 bits per byte); `tx_buffer_bytes` ≥ 1. Throws
  /// std::invalid_argument naming the value otherwise.
  PacedLine(int baud, size_t tx_buffer_bytes);

  /// Queues `bytes` at `now_s`; returns false and queues nothing if they do not fit the transmit
  /// buffer beside the bytes still unsent at `now_s`.
  bool Queue(std::span<const uint8_t> bytes, double now_s);

  /// Appends to `out` every byte whose last bit has left the line by `now_s`.
  void Release(double now_s, std::vector<uint8_t>& out);

  /// Drops every byte still unsent at `now_s` (a power loss empties the buffer, possibly
  /// mid-frame); bytes already on the wire by then are still released.
  void Flush(double now_s);

  /// Seconds per byte on the line.
  double byte_time_s() const { return byte_time_s_; }
  int baud() const { return baud_; }

 private:
  struct Byte {
    double end_s;
    uint8_t value;
  };
  size_t UnsentAt(double now_s) const;

  int baud_;
  double byte_time_s_;
  size_t tx_buffer_bytes_;
  double line_free_s_ = 0.0;  // when the last queued byte's stop bit ends
  std::deque<Byte> queue_;
};

}  // namespace adahrs::rig_sim
