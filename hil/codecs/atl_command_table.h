// The command table of the Ideal Aerosmith Table Language (ATL) as data: which mnemonics exist,
// what argument each takes (type, limits, unit), whether it has a query form (`MNE?`), the reply
// template of each form, the framing (line end, prompt, echo) and the error reply templates. Data
// because no ATL manual was found (shared/protocols.md §1.1): the default table
// (rig_sim/data/atl_commands.json) marks each entry DOC / DRV / INF / UNKNOWN so the lab can
// correct the wire syntax from the Aero 800 manual without touching code. The virtual table and the
// pipeline's driver both use it; the device binds each command's `operation`, not its spelling.
// Units: each argument's limits in the unit the entry names (deg/s, deg/s^2, deg, Hz).
// Templates, strict loading (ParamError naming the file and JSON path) and the commands:
// docs/rig/rate-table.md (the command table, "Framing", "Commands", "Refusals").
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace adahrs::hil {

enum class AtlArgument { kNone, kInteger, kReal };

/// One form of a command: the bare form `MNE [arg]` (an action) or the query form `MNE?`.
struct AtlForm {
  AtlArgument argument = AtlArgument::kNone;
  double min = 0.0;  ///< argument limits (inclusive), in `unit`
  double max = 0.0;
  std::string unit;        ///< as printed in messages ("deg/s")
  std::string reply;       ///< data template with {value}; empty: the form returns no data
  int decimals = 0;        ///< digits after the point when {value} is printed
  std::string confidence;  ///< DOC / DRV / INF / UNKNOWN
};

struct AtlCommandSpec {
  std::string mnemonic;   ///< upper case, letters only ("JOG", "P")
  std::string operation;  ///< controller function the device binds ("rate", "move", …)
  std::string confidence;
  std::string meaning;
  std::optional<AtlForm> action;  ///< present when `MNE [arg]` is accepted
  std::optional<AtlForm> query;   ///< present when `MNE?` is accepted
};

/// Error reply templates (each one line of data, framed like any reply).
struct AtlErrorTemplates {
  std::string unknown_command;
  std::string bad_argument;
  std::string out_of_range;
  std::string servo_off;
  std::string interlock_open;
  std::string line_too_long;
  std::string confidence;
};

struct AtlFraming {
  std::string line_end = "\r\n";
  std::string prompt = ">";
  bool echo = false;
  size_t max_line_chars = 64;
  std::string confidence;
};

class AtlCommandTable {
 public:
  /// Reads a table file; throws common::ParamError naming the file and JSON path.
  static AtlCommandTable Load(const std::string& file_path);
  /// Reads a table already parsed; `source` names it in messages.
  static AtlCommandTable FromJson(const nlohmann::json& table, const std::string& source);

  /// The entry for `mnemonic` (upper case), or nullptr.
  const AtlCommandSpec* Find(std::string_view mnemonic) const;
  /// The entry bound to `operation`, or nullptr (the first if several).
  const AtlCommandSpec* FindOperation(std::string_view operation) const;

  const std::vector<AtlCommandSpec>& commands() const { return commands_; }
  const AtlFraming& framing() const { return framing_; }
  const AtlErrorTemplates& errors() const { return errors_; }

 private:
  std::vector<AtlCommandSpec> commands_;
  AtlFraming framing_;
  AtlErrorTemplates errors_;
};

}  // namespace adahrs::hil
