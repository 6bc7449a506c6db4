#include "hil/codecs/scpi.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace adahrs::hil {
namespace {

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
char Upper(char c) { return static_cast<char>(std::toupper(static_cast<unsigned char>(c))); }

std::string_view Trim(std::string_view s) {
  while (!s.empty() && IsSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && IsSpace(s.back())) s.remove_suffix(1);
  return s;
}

ScpiParsed Error(int code, size_t offset, std::string reason) {
  ScpiParsed parsed;
  parsed.error = code;
  parsed.offset = offset;
  parsed.reason = std::move(reason);
  return parsed;
}

}  // namespace

std::string_view ScpiErrorMessage(int code) {
  switch (code) {
    case kScpiNoError:
      return "No error";
    case kScpiCommandError:
      return "Command error";
    case kScpiSyntaxError:
      return "Syntax error";
    case kScpiDataTypeError:
      return "Data type error";
    case kScpiParameterNotAllowed:
      return "Parameter not allowed";
    case kScpiMissingParameter:
      return "Missing parameter";
    case kScpiUndefinedHeader:
      return "Undefined header";
    case kScpiSettingsConflict:
      return "Settings conflict";
    case kScpiDataOutOfRange:
      return "Data out of range";
    case kScpiIllegalParameterValue:
      return "Illegal parameter value";
    case kScpiQueryInterrupted:
      return "Query INTERRUPTED";
    default:
      return "Error";
  }
}

std::vector<std::string> SplitScpiProgram(std::string_view line) {
  std::vector<std::string> commands;
  std::string current;
  char quote = 0;
  for (const char c : Trim(line)) {
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == ';') {
      commands.push_back(std::string(Trim(current)));
      current.clear();
      continue;
    }
    current.push_back(c);
  }
  if (!Trim(current).empty() || !commands.empty()) commands.push_back(std::string(Trim(current)));
  return commands;
}

ScpiParsed ParseScpiCommand(std::string_view text) {
  for (size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if ((c < 0x20 && !IsSpace(text[i])) || c > 0x7E)
      return Error(kScpiSyntaxError, i, "invalid character");
  }
  ScpiCommand command;
  size_t i = 0;
  while (i < text.size() && IsSpace(text[i])) ++i;
  if (i == text.size()) return Error(kScpiSyntaxError, i, "empty command");
  if (text[i] == '*') {
    command.common = true;
    ++i;
  } else if (text[i] == ':') {
    ++i;
  }
  // Header: mnemonics of letters, digits and '_' (a letter first), separated by ':'.
  while (true) {
    const size_t start = i;
    while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_'))
      ++i;
    if (i == start || !std::isalpha(static_cast<unsigned char>(text[start]))) {
      return Error(kScpiSyntaxError, start, "a mnemonic must start with a letter");
    }
    if (i - start > 12)
      return Error(kScpiSyntaxError, start + 12, "mnemonic longer than 12 characters");
    std::string mnemonic;
    for (size_t k = start; k < i; ++k) mnemonic.push_back(Upper(text[k]));
    command.headers.push_back(std::move(mnemonic));
    if (i < text.size() && text[i] == ':' && !command.common) {
      ++i;
      continue;
    }
    break;
  }
  if (i < text.size() && text[i] == '?') {
    command.query = true;
    ++i;
  }
  if (i < text.size() && !IsSpace(text[i]))
    return Error(kScpiSyntaxError, i, "header followed by no space");
  const std::string_view rest = Trim(text.substr(i));
  if (!rest.empty()) {
    size_t start = 0;
    char quote = 0;
    for (size_t k = 0; k <= rest.size(); ++k) {
      if (k < rest.size() && quote) {
        if (rest[k] == quote) quote = 0;
      } else if (k < rest.size() && (rest[k] == '"' || rest[k] == '\'')) {
        quote = rest[k];
      } else if (k == rest.size() || rest[k] == ',') {
        const std::string_view arg = Trim(rest.substr(start, k - start));
        if (arg.empty()) return Error(kScpiSyntaxError, i + k, "empty argument");
        command.args.emplace_back(arg);
        start = k + 1;
      }
    }
    if (quote) return Error(kScpiSyntaxError, text.size(), "unterminated string");
  }
  ScpiParsed parsed;
  parsed.command = std::move(command);
  return parsed;
}

bool ScpiHeaderMatches(std::string_view pattern, std::string_view given) {
  std::string short_form, long_form, upper_given;
  for (const char c : pattern) {
    if (std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)))
      short_form.push_back(c);
    long_form.push_back(Upper(c));
  }
  for (const char c : given) upper_given.push_back(Upper(c));
  return upper_given == short_form || upper_given == long_form;
}

bool ScpiHeadersMatch(const ScpiCommand& command, const std::vector<std::string_view>& patterns) {
  if (command.headers.size() != patterns.size()) return false;
  for (size_t i = 0; i < patterns.size(); ++i) {
    if (!ScpiHeaderMatches(patterns[i], command.headers[i])) return false;
  }
  return true;
}

std::optional<double> ParseScpiNumber(std::string_view text) {
  // NR1/NR2/NR3 (IEEE 488.2 §7.7.2): [sign] digits [. digits] [E [sign] digits], a digit required.
  size_t i = 0;
  auto digits = [&] {
    const size_t start = i;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i;
    return i - start;
  };
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  size_t mantissa = digits();
  if (i < text.size() && text[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return std::nullopt;
  if (i < text.size() && (text[i] == 'E' || text[i] == 'e')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (digits() == 0) return std::nullopt;
  }
  if (i != text.size()) return std::nullopt;
  const double value = std::strtod(std::string(text).c_str(), nullptr);
  if (!std::isfinite(value)) return std::nullopt;
  return value;
}

std::string FormatScpiNumber(double value, int significant_digits) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*g", significant_digits, value == 0.0 ? 0.0 : value);
  return text;
}

}  // namespace adahrs::hil
