#include "hil/drivers/virtual_fixture_operator.h"

#include <algorithm>
#include <array>
#include <ostream>

#include <fmt/format.h>

#include "hil/drivers/unit_link.h"
#include "hil/instruments/instrument_error.h"

namespace adahrs::hil {
namespace {

using Kind = InstrumentError::Kind;
constexpr const char* kRole = "operator";

std::unique_ptr<SerialPort> OpenControlPort(const OperatorEntry& entry) {
  try {
    // Shared: the rig's control port serves every bench's operator and the test tools.
    return std::make_unique<SerialPort>(entry.port, kRole, PortAccess::kShared);
  } catch (const TransportError& e) {
    throw InstrumentError(Kind::kNoReply, kRole, entry.port.path, "open", "", e.what());
  }
}

std::string Trim(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

}  // namespace

VirtualFixtureOperator::VirtualFixtureOperator(const OperatorEntry& entry,
                                               const Clock& clock,
                                               std::ostream& log)
    : clock_(clock), log_(log), port_(OpenControlPort(entry)) {}

std::string VirtualFixtureOperator::Command(const std::string& line) {
  const std::chrono::milliseconds timeout =
      std::max(kMinWallReplyTimeout, clock_.WallTimeout(kControlReplyTimeoutS));
  std::string received;
  try {
    port_->DiscardInput();
    port_->Write(line + "\n", timeout);
    // The rig's clock may stand still while it waits for a slow reader (lockstep): the reply
    // is late only once that clock, too, has passed the promised time.
    const ReplyDeadline deadline(clock_, kControlReplyTimeoutS, timeout);
    std::array<uint8_t, 256> chunk{};
    while (!deadline.Passed()) {
      const size_t n = port_->ReadSome(chunk, deadline.WaitLeft());
      received.append(reinterpret_cast<const char*>(chunk.data()), n);
      const size_t end = received.find('\n');
      if (end != std::string::npos) return Trim(received.substr(0, end + 1));
    }
  } catch (const TransportError& e) {
    throw InstrumentError(Kind::kNoReply, kRole, port_->path(), line, received, e.what());
  }
  throw InstrumentError(Kind::kNoReply,
                        kRole,
                        port_->path(),
                        line,
                        received,
                        fmt::format("no reply line within {} ms wall", timeout.count()));
}

void VirtualFixtureOperator::Mount(const std::vector<std::string>& unit_roles,
                                   int orientation_code) {
  for (const std::string& role : unit_roles) {
    const std::string line = fmt::format("orientation {} {}", role, orientation_code);
    const std::string reply = Command(line);
    if (reply != fmt::format("OK {} {}", role, orientation_code)) {
      throw InstrumentError(Kind::kRefused,
                            kRole,
                            port_->path(),
                            line,
                            reply,
                            "the virtual fixture did not mount the unit");
    }
  }
}

void VirtualFixtureOperator::Prompt(const std::string& text) {
  log_ << "operator (virtual fixture): " << text << std::endl;
}

}  // namespace adahrs::hil
