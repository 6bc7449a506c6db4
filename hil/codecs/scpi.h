// Generic SCPI / IEEE 488.2 program-message parsing and reply formatting (SCPI-1999 vol. 1 ch. 6-7;
// IEEE 488.2 §7), enough for the instruments on our benches (the Druck ADTS, protocols.md §4.2).
//
// A line is one or more commands separated by `;`. A command is a common command (`*IDN?`) or a
// header of `:`-separated mnemonics (`SOUR:PRES`, leading `:` optional), an optional `?`, then
// whitespace and comma-separated arguments. Mnemonics match in their short or long form
// (ScpiHeaderMatches("SOURce", "SOUR") and ("SOURce", "SOURCE")), case-insensitively.
// Errors are SCPI error numbers: -102 syntax error, -113 undefined header (for the instrument to
// raise), -222 data out of range, -224 illegal parameter value and so on.
// Not here: the tree context rule of `;` (each command is taken from the root), numeric suffixes,
// block and expression data, units on numbers; the instrument's command table.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace adahrs::hil {

inline constexpr int kScpiNoError = 0;
inline constexpr int kScpiCommandError = -100;
inline constexpr int kScpiSyntaxError = -102;
inline constexpr int kScpiDataTypeError = -104;
inline constexpr int kScpiParameterNotAllowed = -108;
inline constexpr int kScpiMissingParameter = -109;
inline constexpr int kScpiUndefinedHeader = -113;
inline constexpr int kScpiSettingsConflict = -221;
inline constexpr int kScpiDataOutOfRange = -222;
inline constexpr int kScpiIllegalParameterValue = -224;
inline constexpr int kScpiQueryInterrupted = -410;  ///< IEEE 488.2 §6.3.2.3

/// The standard message of a SCPI error number ("Undefined header"), or "Error".
std::string_view ScpiErrorMessage(int code);

struct ScpiCommand {
  bool common = false;               ///< `*XXX`
  std::vector<std::string> headers;  ///< mnemonics upper-cased, without `*` and `?`
  bool query = false;
  std::vector<std::string> args;  ///< trimmed, quotes kept
};

/// A parsed command, or the SCPI error number, the offset in the command text and why.
struct ScpiParsed {
  std::optional<ScpiCommand> command;
  int error = kScpiNoError;
  size_t offset = 0;
  std::string reason;
};

/// Splits a program message into commands at `;` outside quoted strings, after removing the
/// trailing terminator (LF, CR LF, or trailing whitespace). Never throws.
std::vector<std::string> SplitScpiProgram(std::string_view line);
/// Parses one command. Never throws: any text gives a command or an error.
ScpiParsed ParseScpiCommand(std::string_view text);
/// True when `given` (any case) is the short form (the capitals of `pattern`) or the long form.
bool ScpiHeaderMatches(std::string_view pattern, std::string_view given);
/// True when the command's headers match `patterns` one by one (`{"SOURce", "PRESsure"}`).
bool ScpiHeadersMatch(const ScpiCommand& command, const std::vector<std::string_view>& patterns);
/// A decimal numeric program datum (NR1/NR2/NR3: `12`, `-1.5`, `2.0E+3`), or nullopt.
std::optional<double> ParseScpiNumber(std::string_view text);
/// A number as an NR3/NR2 reply field with `significant_digits` digits (`%.*g`).
std::string FormatScpiNumber(double value, int significant_digits);

}  // namespace adahrs::hil
