#include "rig_sim/paced_line.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace adahrs::rig_sim {
namespace {

constexpr double kBitsPerByte8N1 = 10.0;  // start bit, 8 data bits, stop bit
// Release tolerance: byte end times are sums of doubles; 1 ns is far below one bit (8.7 µs at
// 115,200 baud) and far above their rounding.
constexpr double kTimeEpsilon_s = 1e-9;

}  // namespace

PacedLine::PacedLine(int baud, size_t tx_buffer_bytes)
    : baud_(baud), byte_time_s_(kBitsPerByte8N1 / baud), tx_buffer_bytes_(tx_buffer_bytes) {
  if (baud < 300 || baud > 4000000) {
    throw std::invalid_argument("line rate " + std::to_string(baud) + " baud not in 300…4000000");
  }
  if (tx_buffer_bytes == 0) throw std::invalid_argument("transmit buffer of 0 bytes");
}

size_t PacedLine::UnsentAt(double now_s) const {
  // Bytes end in increasing time order: count from the back.
  size_t unsent = 0;
  for (auto it = queue_.rbegin(); it != queue_.rend() && it->end_s > now_s + kTimeEpsilon_s; ++it) {
    ++unsent;
  }
  return unsent;
}

bool PacedLine::Queue(std::span<const uint8_t> bytes, double now_s) {
  if (UnsentAt(now_s) + bytes.size() > tx_buffer_bytes_) return false;
  double end_s = std::max(now_s, line_free_s_);
  for (uint8_t b : bytes) {
    end_s += byte_time_s_;
    queue_.push_back({end_s, b});
  }
  line_free_s_ = end_s;
  return true;
}

void PacedLine::Release(double now_s, std::vector<uint8_t>& out) {
  while (!queue_.empty() && queue_.front().end_s <= now_s + kTimeEpsilon_s) {
    out.push_back(queue_.front().value);
    queue_.pop_front();
  }
}

void PacedLine::Flush(double now_s) {
  while (!queue_.empty() && queue_.back().end_s > now_s + kTimeEpsilon_s) queue_.pop_back();
  line_free_s_ = std::min(line_free_s_, now_s);
}

}  // namespace adahrs::rig_sim
