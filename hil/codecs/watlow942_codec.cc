#include "hil/codecs/watlow942_codec.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace adahrs::hil {
namespace {

struct Token {
  std::string_view text;
  size_t offset;
};

std::vector<Token> SplitOnSpaces(std::string_view line) {
  std::vector<Token> tokens;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && line[i] == ' ') ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ') ++i;
    if (i > start) tokens.push_back({line.substr(start, i - start), start});
  }
  return tokens;
}

Watlow942Decoded Fail(Watlow942Error error, size_t offset, std::string reason) {
  Watlow942Decoded decoded;
  decoded.error = error;
  decoded.offset = offset;
  decoded.reason = std::move(reason);
  return decoded;
}

// Numeric datum (p. 10): optional leading sign, digits, at most one decimal point, at least one
// digit. Returns the offset of the first bad character within the token, or npos when valid.
size_t FirstBadNumberChar(std::string_view token) {
  bool seen_point = false;
  bool seen_digit = false;
  for (size_t i = 0; i < token.size(); ++i) {
    const char c = token[i];
    if ((c == '-' || c == '+') && i == 0) continue;
    if (c == '.' && !seen_point) {
      seen_point = true;
      continue;
    }
    if (std::isdigit(static_cast<unsigned char>(c))) {
      seen_digit = true;
      continue;
    }
    return i;
  }
  return seen_digit ? std::string_view::npos : token.size() - 1;
}

}  // namespace

Watlow942Decoded DecodeWatlow942Line(std::string_view line) {
  for (size_t i = 0; i < line.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(line[i]);
    if (c < 0x20 || c > 0x7E)
      return Fail(Watlow942Error::kInvalidCharacter, i, "non-printable byte");
  }
  const std::vector<Token> tokens = SplitOnSpaces(line);
  if (tokens.empty()) return Fail(Watlow942Error::kIncompleteCommandLine, 0, "empty line");
  Watlow942Message message;
  if (tokens[0].text == "?") {
    message.command = Watlow942Command::kRead;
  } else if (tokens[0].text == "=") {
    message.command = Watlow942Command::kWrite;
  } else {
    return Fail(Watlow942Error::kCommandNotFound, tokens[0].offset, "command is neither ? nor =");
  }
  if (tokens.size() < 2) {
    return Fail(Watlow942Error::kIncompleteCommandLine, line.size(), "no parameter mnemonic");
  }
  const Token& mnemonic = tokens[1];
  for (size_t i = 0; i < mnemonic.text.size(); ++i) {
    if (!std::isalnum(static_cast<unsigned char>(mnemonic.text[i]))) {
      return Fail(Watlow942Error::kInvalidCharacter,
                  mnemonic.offset + i,
                  "mnemonic characters are letters and digits");
    }
    message.mnemonic +=
        static_cast<char>(std::toupper(static_cast<unsigned char>(mnemonic.text[i])));
  }
  if (mnemonic.text.size() > kWatlow942MaxMnemonicChars) {
    return Fail(Watlow942Error::kTooManyCharacters,
                mnemonic.offset + kWatlow942MaxMnemonicChars,
                "mnemonic longer than 4 characters");
  }
  for (size_t t = 2; t < tokens.size(); ++t) {
    const Token& datum = tokens[t];
    const size_t bad = FirstBadNumberChar(datum.text);
    if (bad != std::string_view::npos) {
      return Fail(Watlow942Error::kInvalidCharacter, datum.offset + bad, "datum is not a number");
    }
    if (datum.text.size() > kWatlow942MaxNumberChars) {
      return Fail(Watlow942Error::kTooManyCharacters,
                  datum.offset + kWatlow942MaxNumberChars,
                  "datum longer than 7 characters");
    }
    message.data.push_back(std::strtod(std::string(datum.text).c_str(), nullptr));
  }
  if (message.command == Watlow942Command::kWrite && message.data.empty()) {
    return Fail(Watlow942Error::kIncompleteCommandLine, line.size(), "= without data");
  }
  Watlow942Decoded decoded;
  decoded.message = std::move(message);
  return decoded;
}

std::optional<Watlow942LineSplitter::Line> Watlow942LineSplitter::Feed(uint8_t byte) {
  if (byte == kWatlow942Xon || byte == kWatlow942Xoff) {
    flow_paused_ = byte == kWatlow942Xoff;
    return std::nullopt;
  }
  // A line feed after the CR (terminal programs send CR LF) is not part of any message.
  if (byte == '\n') return std::nullopt;
  if (byte == kWatlow942Cr) {
    Line line{std::move(line_), overflowed_};
    line_.clear();
    overflowed_ = false;
    return line;
  }
  if (line_.size() >= max_line_chars_) {
    overflowed_ = true;
  } else {
    line_.push_back(static_cast<char>(byte));
  }
  return std::nullopt;
}

std::optional<std::string> FormatWatlow942Number(double value, int decimals) {
  if (!std::isfinite(value) || decimals < 0 || decimals > 5) return std::nullopt;
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  std::string formatted(text);
  if (formatted == "-0" || formatted.find_first_not_of("-0.") == std::string::npos) {
    formatted.erase(0, formatted[0] == '-' ? 1 : 0);
  }
  if (formatted.size() > kWatlow942MaxNumberChars) return std::nullopt;
  return formatted;
}

std::string EncodeWatlow942Request(Watlow942Command command,
                                   std::string_view mnemonic,
                                   const std::vector<std::string>& data) {
  std::string line(command == Watlow942Command::kRead ? "? " : "= ");
  line += mnemonic;
  for (const std::string& datum : data) line += " " + datum;
  line.push_back(static_cast<char>(kWatlow942Cr));
  return line;
}

std::string EncodeWatlow942ReadReply(const std::vector<std::string>& fields) {
  std::string reply{static_cast<char>(kWatlow942Xoff), static_cast<char>(kWatlow942Xon)};
  for (size_t i = 0; i < fields.size(); ++i) reply += (i ? " " : "") + fields[i];
  reply.push_back(static_cast<char>(kWatlow942Cr));
  return reply;
}

std::optional<std::string> DecodeWatlow942ReadReply(std::string_view bytes) {
  std::string text;
  for (const char c : bytes) {
    const auto byte = static_cast<uint8_t>(c);
    if (byte == kWatlow942Xon || byte == kWatlow942Xoff) continue;
    if (byte == kWatlow942Cr) return text;
    text.push_back(c);
  }
  return std::nullopt;
}

}  // namespace adahrs::hil
