#include "hil/codecs/atl_codec.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace adahrs::hil {
namespace {

bool IsSpace(char c) { return c == ' ' || c == '\t'; }
bool IsLetter(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
char Upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c; }

std::string_view Trim(std::string_view s) {
  while (!s.empty() && IsSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && IsSpace(s.back())) s.remove_suffix(1);
  return s;
}

// Parses the whole of `text` as a number of the form's type; nullopt when it is not one.
std::optional<double> ParseNumber(std::string_view text, AtlArgument type) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty() || text.front() == '+') return std::nullopt;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (type == AtlArgument::kInteger) {
    long long value = 0;
    const auto [end, ec] = std::from_chars(first, last, value);
    if (ec != std::errc() || end != last) return std::nullopt;
    return static_cast<double>(value);
  }
  double value = 0.0;
  const auto [end, ec] = std::from_chars(first, last, value, std::chars_format::fixed);
  if (ec != std::errc() || end != last || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::string PrintLimit(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", x);
  return buffer;
}

void ReplaceAll(std::string& text, std::string_view key, std::string_view value) {
  for (size_t at = text.find(key); at != std::string::npos;
       at = text.find(key, at + value.size())) {
    text.replace(at, key.size(), value);
  }
}

}  // namespace

std::optional<AtlLine> AtlLineFramer::Push(uint8_t byte) {
  if (byte == '\r' || byte == '\n') {
    if (text_.empty() && !overflowed_) return std::nullopt;
    AtlLine line{std::move(text_), overflowed_};
    text_.clear();
    overflowed_ = false;
    return line;
  }
  if (text_.size() < max_line_chars_) {
    text_.push_back(static_cast<char>(byte));
  } else {
    overflowed_ = true;
  }
  return std::nullopt;
}

AtlParsed ParseAtlLine(const AtlCommandTable& table, const AtlLine& line) {
  AtlParsed out;
  if (line.overflowed) {
    out.status = AtlParseStatus::kLineTooLong;
    return out;
  }
  std::string_view rest = Trim(line.text);
  while (!rest.empty() && IsLetter(rest.front())) {
    out.mnemonic.push_back(Upper(rest.front()));
    rest.remove_prefix(1);
  }
  const AtlCommandSpec* spec = out.mnemonic.empty() ? nullptr : table.Find(out.mnemonic);
  if (spec == nullptr) {
    out.status = AtlParseStatus::kUnknownCommand;
    return out;
  }
  out.query = !rest.empty() && rest.front() == '?';
  if (out.query) rest.remove_prefix(1);
  const std::optional<AtlForm>& form = out.query ? spec->query : spec->action;
  if (!form) {
    out.status = AtlParseStatus::kUnknownCommand;
    return out;
  }
  out.spec = spec;
  rest = Trim(rest);
  out.argument_text = std::string(rest);
  if (form->argument == AtlArgument::kNone) {
    out.status = rest.empty() ? AtlParseStatus::kOk : AtlParseStatus::kBadArgument;
    return out;
  }
  const std::optional<double> value = ParseNumber(rest, form->argument);
  if (!value) {
    out.status = AtlParseStatus::kBadArgument;
    return out;
  }
  out.argument = *value;
  out.status = (*value < form->min || *value > form->max) ? AtlParseStatus::kOutOfRange
                                                          : AtlParseStatus::kOk;
  return out;
}

std::string FrameAtlReply(const AtlFraming& framing, std::string_view data) {
  std::string bytes(data);
  bytes += framing.line_end;
  bytes += framing.prompt;
  bytes += framing.line_end;
  return bytes;
}

std::string FormatAtlValue(const AtlForm& form, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", form.decimals, value);
  std::string number = buffer;
  // A value that rounds to zero prints as 0, never as -0.000.
  if (number.front() == '-' && number.find_first_not_of("-0.") == std::string::npos) {
    number.erase(0, 1);
  }
  std::string data = form.reply;
  ReplaceAll(data, "{value}", number);
  return data;
}

std::string FormatAtlError(std::string_view error_template,
                           const AtlParsed& parsed,
                           std::string_view line,
                           std::optional<std::pair<double, double>> limits) {
  std::string data(error_template);
  ReplaceAll(data, "{line}", line);
  ReplaceAll(data, "{mnemonic}", parsed.mnemonic);
  ReplaceAll(data, "{argument}", parsed.argument_text);
  const AtlForm* form = nullptr;
  if (parsed.spec != nullptr) {
    form = parsed.query ? &*parsed.spec->query : &*parsed.spec->action;
  }
  if (form != nullptr && form->argument == AtlArgument::kNone) form = nullptr;
  if (form != nullptr && !limits) limits = std::make_pair(form->min, form->max);
  ReplaceAll(data, "{min}", limits ? PrintLimit(limits->first) : "");
  ReplaceAll(data, "{max}", limits ? PrintLimit(limits->second) : "");
  ReplaceAll(data, "{unit}", form ? form->unit : "");
  return data;
}

const std::string& AtlErrorTemplateFor(const AtlCommandTable& table, AtlParseStatus status) {
  switch (status) {
    case AtlParseStatus::kBadArgument:
      return table.errors().bad_argument;
    case AtlParseStatus::kOutOfRange:
      return table.errors().out_of_range;
    case AtlParseStatus::kLineTooLong:
      return table.errors().line_too_long;
    case AtlParseStatus::kOk:
    case AtlParseStatus::kUnknownCommand:
      break;
  }
  return table.errors().unknown_command;
}

std::string EncodeAtlCommand(const AtlCommandTable& table,
                             std::string_view mnemonic,
                             std::optional<double> argument,
                             bool query) {
  const std::string name(mnemonic);
  const AtlCommandSpec* spec = table.Find(name);
  if (spec == nullptr) throw std::invalid_argument("ATL: no command " + name + " in the table");
  const std::optional<AtlForm>& form = query ? spec->query : spec->action;
  if (!form) {
    throw std::invalid_argument("ATL: " + name + (query ? " has no query form" : " is query-only"));
  }
  std::string bytes = name;
  if (query) bytes += "?";
  if (form->argument == AtlArgument::kNone) {
    if (argument) throw std::invalid_argument("ATL: " + name + " takes no argument");
  } else {
    if (!argument) throw std::invalid_argument("ATL: " + name + " needs an argument");
    const double x = *argument;
    if (!std::isfinite(x) || x < form->min || x > form->max) {
      throw std::invalid_argument("ATL: " + name + " " + PrintLimit(x) + " is outside [" +
                                  PrintLimit(form->min) + ", " + PrintLimit(form->max) + "] " +
                                  form->unit);
    }
    if (form->argument == AtlArgument::kInteger && std::floor(x) != x) {
      throw std::invalid_argument("ATL: " + name + " takes an integer, not " + PrintLimit(x));
    }
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::fixed);
    bytes += " ";
    bytes.append(buffer, result.ptr);
  }
  bytes += table.framing().line_end;
  return bytes;
}

AtlReplyReader::AtlReplyReader(const AtlFraming& framing)
    : terminator_(framing.line_end + framing.prompt + framing.line_end) {}

std::vector<std::string> AtlReplyReader::Push(std::span<const uint8_t> bytes) {
  buffer_.append(bytes.begin(), bytes.end());
  std::vector<std::string> replies;
  for (size_t at = buffer_.find(terminator_); at != std::string::npos;
       at = buffer_.find(terminator_)) {
    replies.push_back(buffer_.substr(0, at));
    buffer_.erase(0, at + terminator_.size());
  }
  return replies;
}

}  // namespace adahrs::hil
