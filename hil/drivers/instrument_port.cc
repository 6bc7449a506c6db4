#include "hil/drivers/instrument_port.h"

#include <algorithm>
#include <array>

#include <fmt/format.h>

namespace adahrs::hil {

std::chrono::milliseconds WallReplyTimeout(const Clock& clock, int timeout_ms) {
  return std::max(kMinWallReplyTimeout, clock.WallTimeout(timeout_ms / 1000.0));
}

namespace {

std::unique_ptr<SerialPort> OpenInstrumentPort(const InstrumentEntry& entry) {
  try {
    return std::make_unique<SerialPort>(entry.port, entry.role);
  } catch (const TransportError& e) {
    throw InstrumentError(
        InstrumentError::Kind::kNoReply, entry.role, entry.port.path, "open", "", e.what());
  }
}

}  // namespace

InstrumentPort::InstrumentPort(const InstrumentEntry& entry, const Clock& clock)
    : entry_(entry), clock_(clock), port_(OpenInstrumentPort(entry)) {}

void InstrumentPort::Fail(InstrumentError::Kind kind,
                          const std::string& command,
                          const std::string& reply,
                          const std::string& detail) const {
  throw InstrumentError(kind, entry_.role, entry_.port.path, command, reply, detail);
}

void InstrumentPort::Send(const std::string& command, std::string_view request) {
  try {
    port_->Write(request, reply_timeout());
  } catch (const TransportError& e) {
    Fail(InstrumentError::Kind::kNoReply, command, "", e.what());
  }
}

size_t InstrumentPort::DrainUntilQuiet(const std::string& command, double quiet_s) {
  const ReplyDeadline limit(clock_, entry_.timeout_ms / 1000.0, reply_timeout());
  ReplyDeadline quiet(clock_, quiet_s, std::max(kMinWallQuiet, clock_.WallTimeout(quiet_s)));
  size_t dropped = 0;
  std::array<uint8_t, 256> chunk{};
  while (!quiet.Passed() && !limit.Passed()) {
    size_t n = 0;
    try {
      n = port_->ReadSome(chunk, std::min(quiet.WaitLeft(), limit.WaitLeft()));
    } catch (const TransportError& e) {
      Fail(InstrumentError::Kind::kNoReply, command, "", e.what());
    }
    if (n > 0) {
      dropped += n;
      quiet.Restart();
    }
  }
  return dropped;
}

std::string InstrumentPort::Exchange(const std::string& command,
                                     std::string_view request,
                                     std::string_view terminator) {
  return ExchangeUntil(command, request, terminator, [](std::string_view) { return true; }).back();
}

std::vector<std::string> InstrumentPort::ExchangeUntil(
    const std::string& command,
    std::string_view request,
    std::string_view terminator,
    const std::function<bool(std::string_view)>& is_answer) {
  std::string received;
  const int attempts = entry_.retries + 1;
  for (int attempt = 0; attempt < attempts; ++attempt) {
    port_->DiscardInput();
    Send(command, request);
    received.clear();
    std::vector<std::string> replies;
    const ReplyDeadline deadline(clock_, entry_.timeout_ms / 1000.0, reply_timeout());
    std::array<uint8_t, 256> chunk{};
    while (!deadline.Passed()) {
      size_t n = 0;
      try {
        n = port_->ReadSome(chunk, deadline.WaitLeft());
      } catch (const TransportError& e) {
        Fail(InstrumentError::Kind::kNoReply, command, received, e.what());
      }
      received.append(reinterpret_cast<const char*>(chunk.data()), n);
      for (size_t at = received.find(terminator); at != std::string::npos;
           at = received.find(terminator)) {
        replies.push_back(received.substr(0, at + terminator.size()));
        received.erase(0, at + terminator.size());
        if (is_answer(replies.back())) return replies;
      }
    }
    if (!replies.empty()) return replies;
  }
  Fail(InstrumentError::Kind::kNoReply,
       command,
       received,
       fmt::format("{} attempts of {} ms wall each", attempts, reply_timeout().count()));
}

}  // namespace adahrs::hil
