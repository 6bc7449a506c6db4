#include "hil/instruments/instrument_error.h"

#include <fmt/format.h>

#include "common/printable_text.h"

namespace adahrs::hil {

namespace {

std::string Compose(InstrumentError::Kind kind,
                    const std::string& role,
                    const std::string& port,
                    const std::string& command,
                    const std::string& reply,
                    const std::string& detail) {
  std::string text =
      fmt::format("{} on {}: {}: {}", role, port, common::PrintableText(command), ToString(kind));
  if (!detail.empty()) text += fmt::format(" ({})", common::PrintableText(detail));
  text += reply.empty() ? std::string("; nothing came back")
                        : fmt::format("; reply '{}'", common::PrintableText(reply));
  return text;
}

}  // namespace

InstrumentError::InstrumentError(Kind kind,
                                 std::string role,
                                 std::string port,
                                 std::string command,
                                 std::string reply,
                                 const std::string& detail)
    : std::runtime_error(Compose(kind, role, port, command, reply, detail)),
      kind_(kind),
      role_(std::move(role)),
      port_(std::move(port)),
      command_(std::move(command)),
      reply_(common::PrintableText(reply)) {}

const char* ToString(InstrumentError::Kind kind) {
  switch (kind) {
    case InstrumentError::Kind::kNoReply:
      return "no reply";
    case InstrumentError::Kind::kRefused:
      return "refused";
    case InstrumentError::Kind::kBadReply:
      return "unexpected reply";
    case InstrumentError::Kind::kWrongIdentity:
      return "wrong identity";
    case InstrumentError::Kind::kFault:
      return "instrument fault";
  }
  return "?";
}

}  // namespace adahrs::hil
