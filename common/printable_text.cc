#include "common/printable_text.h"

#include <cstdint>
#include <cstdio>

namespace adahrs::common {
namespace {

/// Length of the well-formed UTF-8 sequence of a printable code point at `bytes[at]`, or 0.
size_t PrintableUtf8Length(std::string_view bytes, size_t at) {
  const auto lead = static_cast<uint8_t>(bytes[at]);
  size_t length = 0;
  uint32_t code_point = 0;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
    code_point = lead & 0x1Fu;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    code_point = lead & 0x0Fu;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    code_point = lead & 0x07u;
  } else {
    return 0;
  }
  if (at + length > bytes.size()) return 0;
  for (size_t i = 1; i < length; ++i) {
    const auto next = static_cast<uint8_t>(bytes[at + i]);
    if ((next & 0xC0u) != 0x80u) return 0;
    code_point = (code_point << 6) | (next & 0x3Fu);
  }
  const uint32_t shortest[] = {0, 0, 0x80, 0x800, 0x10000};
  const bool overlong = code_point < shortest[length];
  const bool surrogate = code_point >= 0xD800 && code_point <= 0xDFFF;
  const bool c1_control = code_point >= 0x80 && code_point <= 0x9F;
  if (overlong || surrogate || c1_control || code_point > 0x10FFFF) return 0;
  return length;
}

/// `whole_message`: LF and the backslash are kept (a message may quote text already escaped).
std::string Escape(std::string_view bytes, bool whole_message) {
  std::string out;
  out.reserve(bytes.size());
  for (size_t at = 0; at < bytes.size();) {
    const auto byte = static_cast<uint8_t>(bytes[at]);
    if (byte >= 0x80) {
      const size_t length = PrintableUtf8Length(bytes, at);
      if (length > 0) {
        out.append(bytes.substr(at, length));
        at += length;
        continue;
      }
    }
    switch (byte) {
      case '\r':
        out += "\\r";
        break;
      case '\n':
        out += whole_message ? "\n" : "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\\':
        out += whole_message ? "\\" : "\\\\";
        break;
      default:
        if (byte < 0x20 || byte >= 0x7F) {
          char hex[5];
          std::snprintf(hex, sizeof hex, "\\x%02X", byte);
          out += hex;
        } else {
          out += static_cast<char>(byte);
        }
    }
    ++at;
  }
  return out;
}

}  // namespace

std::string PrintableText(std::string_view bytes) { return Escape(bytes, false); }

std::string PrintableMessage(std::string_view message) { return Escape(message, true); }

}  // namespace adahrs::common
