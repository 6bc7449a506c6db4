#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange under g++ 12

#include "hil/transport/serial_port.h"

#include <poll.h>
#include <sys/file.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <boost/asio/io_context.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/serial_port.hpp>
#include <boost/asio/write.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>

namespace adahrs::hil {

namespace asio = boost::asio;

struct SerialPort::Impl {
  asio::io_context io;
  asio::serial_port port{io};
};

namespace {

// Runs the io_context until `done` or the timeout; on timeout cancels the operation and lets its
// handler complete, so no handler outlives the call.
template <typename Done>
bool RunWithTimeout(asio::io_context& io,
                    asio::serial_port& port,
                    std::chrono::milliseconds timeout,
                    Done done) {
  io.restart();
  io.run_for(timeout);
  if (done()) return true;
  boost::system::error_code ignored;
  port.cancel(ignored);
  io.restart();
  io.run();
  return done();
}

}  // namespace

std::string HexBytes(std::span<const uint8_t> bytes, size_t max_bytes) {
  std::string out;
  char cell[4];
  for (size_t i = 0; i < bytes.size() && i < max_bytes; ++i) {
    std::snprintf(cell, sizeof cell, "%02X", bytes[i]);
    if (!out.empty()) out += ' ';
    out += cell;
  }
  if (bytes.size() > max_bytes) out += " … (" + std::to_string(bytes.size()) + " bytes)";
  return out;
}

SerialPort::SerialPort(const SerialSettings& s, std::string role, PortAccess access)
    : impl_(std::make_unique<Impl>()), role_(std::move(role)), path_(s.path), flow_(s.flow) {
  boost::system::error_code ec;
  impl_->port.open(s.path, ec);
  if (ec) throw TransportError(Describe("cannot open: " + ec.message()));
  if (access == PortAccess::kExclusive &&
      ::flock(impl_->port.native_handle(), LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    throw TransportError(Describe(
        error == EWOULDBLOCK ? std::string("in use: another open of this device holds its lock "
                                           "(a second pipeline, or a program opening it "
                                           "exclusively); one client per port")
                             : std::string("cannot lock: ") + std::strerror(error)));
  }
  using P = asio::serial_port_base;
  const auto parity = s.parity == 'E'   ? P::parity::even
                      : s.parity == 'O' ? P::parity::odd
                                        : P::parity::none;
  const auto flow = s.flow == SerialSettings::Flow::kSoftware   ? P::flow_control::software
                    : s.flow == SerialSettings::Flow::kHardware ? P::flow_control::hardware
                                                                : P::flow_control::none;
  impl_->port.set_option(P::baud_rate(s.baud), ec);
  if (!ec) impl_->port.set_option(P::character_size(s.data_bits), ec);
  if (!ec) impl_->port.set_option(P::parity(parity), ec);
  if (!ec)
    impl_->port.set_option(P::stop_bits(s.stop_bits == 2 ? P::stop_bits::two : P::stop_bits::one),
                           ec);
  if (!ec) impl_->port.set_option(P::flow_control(flow), ec);
  if (ec) throw TransportError(Describe("cannot configure: " + ec.message()));
  DiscardInput();
}

SerialPort::~SerialPort() = default;

std::string SerialPort::Describe(const std::string& what) const {
  return role_ + " (" + path_ + "): " + what;
}

void SerialPort::DiscardInput() {
  pending_.clear();
  const int fd = impl_->port.native_handle();
  if (flow_ != SerialSettings::Flow::kSoftware) {
    ::tcflush(fd, TCIFLUSH);
    return;
  }
  // Read what the line discipline has (it has acted on every XON/XOFF among it); bytes still on
  // their way are left to it, and to the reply parser, which skips flow characters.
  std::array<uint8_t, 256> dropped{};
  pollfd ready{fd, POLLIN, 0};
  while (::poll(&ready, 1, 0) > 0 && (ready.revents & POLLIN) != 0) {
    if (::read(fd, dropped.data(), dropped.size()) <= 0) break;
  }
}

void SerialPort::Write(std::span<const uint8_t> bytes, std::chrono::milliseconds timeout) {
  std::optional<boost::system::error_code> result;
  asio::async_write(impl_->port,
                    asio::buffer(bytes.data(), bytes.size()),
                    [&](const boost::system::error_code& ec, size_t) { result = ec; });
  if (!RunWithTimeout(impl_->io, impl_->port, timeout, [&] { return result.has_value(); }) ||
      *result == asio::error::operation_aborted) {
    throw TransportTimeout(Describe("write of " + std::to_string(bytes.size()) +
                                    " bytes timed out after " + std::to_string(timeout.count()) +
                                    " ms"));
  }
  if (*result) throw TransportError(Describe("write failed: " + result->message()));
  if (trace_) trace_(TraceDirection::kSent, bytes);
}

void SerialPort::Write(std::string_view text, std::chrono::milliseconds timeout) {
  Write(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()),
        timeout);
}

size_t SerialPort::ReadSome(std::span<uint8_t> buffer, std::chrono::milliseconds timeout) {
  if (!pending_.empty()) {
    const size_t n = std::min(buffer.size(), pending_.size());
    std::copy_n(pending_.begin(), n, buffer.begin());
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(n));
    return n;
  }
  std::optional<std::pair<boost::system::error_code, size_t>> result;
  impl_->port.async_read_some(
      asio::buffer(buffer.data(), buffer.size()),
      [&](const boost::system::error_code& ec, size_t n) { result.emplace(ec, n); });
  RunWithTimeout(impl_->io, impl_->port, timeout, [&] { return result.has_value(); });
  if (!result || result->first == asio::error::operation_aborted) return 0;
  if (result->first) throw TransportError(Describe("read failed: " + result->first.message()));
  if (trace_ && result->second > 0) {
    trace_(TraceDirection::kReceived, buffer.first(result->second));
  }
  return result->second;
}

std::string SerialPort::ReadUntil(std::string_view terminator, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::string text;
  std::array<uint8_t, 256> chunk{};
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    const size_t n = left.count() > 0 ? ReadSome(chunk, left) : 0;
    text.append(reinterpret_cast<const char*>(chunk.data()), n);
    const size_t at = text.find(terminator);
    if (at != std::string::npos) {
      const size_t end = at + terminator.size();
      pending_.insert(
          pending_.begin(), text.begin() + static_cast<std::ptrdiff_t>(end), text.end());
      text.resize(end);
      return text;
    }
    if (n == 0 && std::chrono::steady_clock::now() >= deadline) {
      throw TransportTimeout(Describe(
          "no reply ending in " +
          HexBytes(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(terminator.data()),
                                            terminator.size())) +
          " within " + std::to_string(timeout.count()) + " ms; received " +
          (text.empty() ? std::string("nothing")
                        : "'" +
                              HexBytes(std::span<const uint8_t>(
                                  reinterpret_cast<const uint8_t*>(text.data()), text.size())) +
                              "'")));
    }
  }
}

std::vector<uint8_t> SerialPort::ReadExactly(size_t count, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::vector<uint8_t> out(count);
  size_t have = 0;
  while (have < count) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    const size_t n = left.count() > 0 ? ReadSome(std::span<uint8_t>(out).subspan(have), left) : 0;
    have += n;
    if (n == 0 && std::chrono::steady_clock::now() >= deadline) {
      out.resize(have);
      throw TransportTimeout(Describe("expected " + std::to_string(count) + " bytes within " +
                                      std::to_string(timeout.count()) + " ms; received " +
                                      std::to_string(have) + ": " + HexBytes(out)));
    }
  }
  return out;
}

}  // namespace adahrs::hil
