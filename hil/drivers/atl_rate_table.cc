#include "hil/drivers/atl_rate_table.h"

#include <stdexcept>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "hil/codecs/atl_codec.h"
#include "hil/drivers/atl_client_table.h"

namespace adahrs::hil {
namespace {

using Kind = InstrumentError::Kind;

// Silence that ends a resynchronisation: several replies' worth at 9600 baud (a 22-character
// refusal takes 23 ms).
constexpr double kResyncQuiet_s = 0.2;

std::string CommandText(const std::string& mnemonic, std::optional<double> argument, bool query) {
  if (query) return mnemonic + "?";
  return argument ? fmt::format("{} {:g}", mnemonic, *argument) : mnemonic;
}

}  // namespace

AtlRateTable::AtlRateTable(const InstrumentEntry& entry, const Clock& clock)
    : port_(entry, clock) {}

std::string AtlRateTable::Command(const std::string& mnemonic,
                                  std::optional<double> argument,
                                  bool query) {
  const AtlCommandTable& table = AtlClientCommandTable();
  const std::string text = CommandText(mnemonic, argument, query);
  std::string request;
  try {
    request = EncodeAtlCommand(table, mnemonic, argument, query);
  } catch (const std::invalid_argument& e) {
    port_.Fail(Kind::kRefused, text, "", std::string("not sent: ") + e.what());
  }
  const AtlFraming& framing = table.framing();
  const std::string terminator = framing.line_end + framing.prompt + framing.line_end;
  // A client that wrote here by mistake (a station with its ports swapped; Modbus bytes hold no
  // line end) leaves a partial line in the table's input, and the table may still be refusing
  // its lines after it closed. The first command is preceded by a line end, which ends that
  // line, and by a wait for the table to fall silent; a refusal later than that wait is skipped.
  const bool resync = !line_synced_;
  if (resync) {
    port_.Send(text, framing.line_end);
    port_.DrainUntilQuiet(text, kResyncQuiet_s);
  }
  const std::vector<std::string> replies =
      port_.ExchangeUntil(text, request, terminator, [resync](std::string_view reply) {
        return !resync || !reply.starts_with('?');
      });
  line_synced_ = true;
  const std::string& reply = replies.back();
  const std::string data = reply.substr(0, reply.size() - terminator.size());
  if (!data.empty() && data.front() == '?') port_.Fail(Kind::kRefused, text, data, "");
  return data;
}

double AtlRateTable::QueryNumber(const std::string& mnemonic) {
  const std::string data = Command(mnemonic, std::nullopt, true);
  try {
    size_t used = 0;
    const double value = std::stod(data, &used);
    if (used == data.size()) return value;
  } catch (const std::exception&) {
  }
  port_.Fail(Kind::kBadReply, mnemonic + "?", data, "expected a number");
}

int AtlRateTable::Status() {
  const double word = QueryNumber("STA");
  if (word < 0 || word != static_cast<int>(word)) {
    port_.Fail(Kind::kBadReply, "STA?", fmt::format("{:g}", word), "expected a status word");
  }
  return static_cast<int>(word);
}

InstrumentIdentity AtlRateTable::Identify() {
  return {"Aerosmith ATL rate table",
          fmt::format("status word {} (no identification query in ATL)", Status())};
}

void AtlRateTable::CommandRate(double rate_dps, double accel_dps2) {
  Command("ACL", accel_dps2, false);
  Command("JOG", rate_dps, false);
}

double AtlRateTable::ReadRateDps() { return QueryNumber("RAT"); }

bool AtlRateTable::AtRate() {
  const int status = Status();
  if (status & (1 << kAtlStatusInterlockOpenBit)) {
    port_.Fail(
        Kind::kFault, "STA?", std::to_string(status), "interlock open: the table is stopped");
  }
  return (status & (1 << kAtlStatusAtRateBit)) != 0;
}

void AtlRateTable::Stop(double accel_dps2) {
  Command("ACL", accel_dps2, false);
  Command("STO", std::nullopt, false);
}

}  // namespace adahrs::hil
