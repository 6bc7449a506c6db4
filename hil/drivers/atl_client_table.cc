#include "hil/drivers/atl_client_table.h"

namespace adahrs::hil {
namespace {

constexpr const char* kTable = R"json({
  "format": "adahrs-atl-command-table-1",
  "about": "The ATL commands the pipeline's rate-table driver sends (subset of rig_sim/data/atl_commands.json).",
  "framing": {
    "confidence": "DRV",
    "note": "Reply = data + CR LF + '>' + CR LF (1270VS control panel).",
    "line_end": "\r\n", "prompt": ">", "echo": false, "max_line_chars": 64
  },
  "errors": {
    "confidence": "UNKNOWN",
    "note": "Error replies start with '?' in the lab's table; their texts are placeholders.",
    "unknown_command": "?UNKNOWN COMMAND",
    "bad_argument": "?BAD ARGUMENT {mnemonic}",
    "out_of_range": "?OUT OF RANGE {mnemonic} {argument} LIMITS {min} {max} {unit}",
    "servo_off": "?SERVO OFF {mnemonic}",
    "interlock_open": "?INTERLOCK OPEN {mnemonic}",
    "line_too_long": "?LINE TOO LONG"
  },
  "commands": [
    {"mnemonic": "JOG", "operation": "rate", "confidence": "DRV",
     "meaning": "Rate mode at the rate, integer deg/s.",
     "action": {"argument": "integer", "min": -360, "max": 360, "unit": "deg/s"}},
    {"mnemonic": "STO", "operation": "stop", "confidence": "DRV",
     "meaning": "Stop all motion at the acceleration setting.",
     "action": {"argument": "none"}},
    {"mnemonic": "ACL", "operation": "acceleration", "confidence": "DRV",
     "meaning": "Acceleration setting, deg/s^2 (unit INF, limits UNKNOWN).",
     "action": {"argument": "real", "min": 0.1, "max": 1000, "unit": "deg/s^2"}},
    {"mnemonic": "RAT", "operation": "measured_rate", "confidence": "UNKNOWN",
     "meaning": "Measured platter rate, deg/s (mnemonic invented).",
     "query": {"confidence": "UNKNOWN", "reply": "{value}", "decimals": 4}},
    {"mnemonic": "STA", "operation": "status", "confidence": "UNKNOWN",
     "meaning": "Status word: bit 0 servo on, 1 at rate, 2 in position, 3 moving, 4 interlock open (invented).",
     "query": {"confidence": "UNKNOWN", "reply": "{value}", "decimals": 0}}
  ]
})json";

}  // namespace

const AtlCommandTable& AtlClientCommandTable() {
  static const AtlCommandTable table =
      AtlCommandTable::FromJson(nlohmann::json::parse(kTable), "hil/drivers/atl_client_table.cc");
  return table;
}

}  // namespace adahrs::hil
