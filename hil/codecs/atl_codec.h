// ATL line codec (pure bytes ↔ messages; no descriptors, no time), for both sides of the line.
//
// Wire format (shared/protocols.md §1.4; confidence per item in the command table):
//   command  `MNE[ ][arg]` or `MNE?`, ended by CR, LF or CR LF (one terminator); mnemonics are
//            the leading letters of the line, case-insensitive (INF); an argument follows with or
//            without spaces (`P90`, `JOG -100`).
//   reply    `<data>` + line_end + prompt + line_end, i.e. "<data>\r\n>\r\n" with the default
//            table (DRV: the 1270VS control panel waits for that terminator); an action's data is
//            empty, so it answers "\r\n>\r\n".
// Server side: AtlLineFramer cuts the byte stream into lines; ParseAtlLine checks a line against
// the table (mnemonic, form, argument type and limits) and returns a typed result, never throws,
// for any bytes. Formatting helpers fill reply and error templates. Client side: EncodeAtlCommand
// formats a command (refusing one the table would refuse) and AtlReplyReader cuts replies.
// Left out: echo handling on the client side, XON/XOFF, any binary or IEEE-488 mode.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hil/codecs/atl_command_table.h"

namespace adahrs::hil {

/// One received line; `overflowed` when more than max_line_chars arrived before its terminator
/// (the text is then the first max_line_chars characters).
struct AtlLine {
  std::string text;
  bool overflowed = false;
};

/// Cuts a byte stream into lines at CR, LF or CR LF. Empty lines are dropped (so the LF of a
/// CR LF pair, or a client's stray terminators, produce nothing).
class AtlLineFramer {
 public:
  explicit AtlLineFramer(size_t max_line_chars) : max_line_chars_(max_line_chars) {}

  /// Feeds one byte; returns a line when `byte` completes one.
  std::optional<AtlLine> Push(uint8_t byte);

 private:
  size_t max_line_chars_;
  std::string text_;
  bool overflowed_ = false;
};

enum class AtlParseStatus {
  kOk,
  kUnknownCommand,  ///< no such mnemonic, or a form the mnemonic does not have
  kBadArgument,     ///< missing, extra, non-numeric or non-integer argument
  kOutOfRange,      ///< a number outside the form's limits
  kLineTooLong,
};

struct AtlParsed {
  AtlParseStatus status = AtlParseStatus::kUnknownCommand;
  const AtlCommandSpec* spec = nullptr;  ///< set when the mnemonic and form exist
  bool query = false;
  double argument = 0.0;      ///< when the form takes one and status is kOk/kOutOfRange
  std::string mnemonic;       ///< as read (upper-cased), for messages
  std::string argument_text;  ///< as read, for messages
};

/// Checks one line against the table.
AtlParsed ParseAtlLine(const AtlCommandTable& table, const AtlLine& line);

/// The reply bytes for `data` (empty for an action): data + line_end + prompt + line_end.
std::string FrameAtlReply(const AtlFraming& framing, std::string_view data);

/// The data of a form's reply template with `value` printed to the form's decimals.
std::string FormatAtlValue(const AtlForm& form, double value);

/// The data of the error reply `error_template` for the parsed line `parsed` (fills {line},
/// {mnemonic}, {argument}, {min}, {max}, {unit}). {min} and {max} are the form's limits unless
/// `limits` gives the limits actually enforced (a table configured narrower than its controller).
std::string FormatAtlError(std::string_view error_template,
                           const AtlParsed& parsed,
                           std::string_view line,
                           std::optional<std::pair<double, double>> limits = std::nullopt);

/// The error template the table gives for a parse failure.
const std::string& AtlErrorTemplateFor(const AtlCommandTable& table, AtlParseStatus status);

/// Client side: the bytes of `mnemonic [argument]` or `mnemonic?`, ended by the table's line end.
/// Throws std::invalid_argument naming the command and the limit when the table would refuse it.
std::string EncodeAtlCommand(const AtlCommandTable& table,
                             std::string_view mnemonic,
                             std::optional<double> argument = std::nullopt,
                             bool query = false);

/// Client side: collects reply bytes and returns each complete reply's data (the text before
/// line_end + prompt + line_end).
class AtlReplyReader {
 public:
  explicit AtlReplyReader(const AtlFraming& framing);
  /// Feeds bytes; returns the data of every reply completed by them, in order.
  std::vector<std::string> Push(std::span<const uint8_t> bytes);
  /// Bytes received that do not yet form a complete reply.
  const std::string& pending() const { return buffer_; }

 private:
  std::string terminator_;
  std::string buffer_;
};

}  // namespace adahrs::hil
