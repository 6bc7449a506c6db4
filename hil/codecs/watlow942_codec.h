// Watlow Series 942 ASCII protocol, XON/XOFF framing (shared/protocols.md §3.2-3.3, DOC: "How to
// Use Data Communications with the Watlow Series 942", pp. 10-14 and 25).
//
// A message is `<command> <space> <Data.1> <space> <Data.2> ... <CR>`: the command is `?` (read)
// or `=` (write); Data.1 is a parameter mnemonic of up to 4 characters, upper or lower case;
// numeric data are up to 7 characters including sign and decimal point (p. 10). The 942 answers a
// `=` line with XOFF (0x13) on the CR and XON (0x11) when done, and a `?` line with
// `<XOFF><XON>value<CR>` (p. 13). Errors are never sent; they are latched in `ER2` (p. 25), whose
// codes are listed in Watlow942Error.
//
// This file is pure bytes ↔ message, used by the virtual 942 (rig_sim) and by the client driver.
// Not here: the ANSI X3.28 framing (§3.4; the 942 uses it only on RS-422/485 multidrop), the
// parameter table and its limits (the device's business).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace adahrs::hil {

inline constexpr uint8_t kWatlow942Xon = 0x11;
inline constexpr uint8_t kWatlow942Xoff = 0x13;
inline constexpr uint8_t kWatlow942Cr = 0x0D;
/// Longest parameter mnemonic (p. 10).
inline constexpr size_t kWatlow942MaxMnemonicChars = 4;
/// Longest numeric datum including sign and decimal point (p. 10).
inline constexpr size_t kWatlow942MaxNumberChars = 7;

/// `ER2` codes (Table 4, p. 18; protocols.md §3.5). 0 = no error.
enum class Watlow942Error : int {
  kNone = 0,
  kRxOverflow = 2,
  kCommandNotFound = 20,
  kParameterNotFound = 21,
  kIncompleteCommandLine = 22,
  kInvalidCharacter = 23,
  kTooManyCharacters = 24,
  kInputOutOfLimit = 25,
  kReadOnly = 26,
  kWriteOnly = 27,
  kRequestToRunInvalid = 30,
  kRequestToHoldInvalid = 31,
  kInvalidInRunMode = 32,
};

enum class Watlow942Command { kRead, kWrite };

/// One decoded message: the mnemonic upper-cased, the data after it as decimal numbers.
struct Watlow942Message {
  Watlow942Command command = Watlow942Command::kRead;
  std::string mnemonic;
  std::vector<double> data;
};

/// A decoded line: a message, or the ER2 code the 942 would latch and why (with the offset of
/// the offending character in the line).
struct Watlow942Decoded {
  std::optional<Watlow942Message> message;
  Watlow942Error error = Watlow942Error::kNone;
  size_t offset = 0;
  std::string reason;
};

/// Decodes one line (without its CR). Never throws; any byte sequence gives a message or an error.
Watlow942Decoded DecodeWatlow942Line(std::string_view line);

/// Splits a byte stream into CR-terminated lines. XON/XOFF bytes are flow control, not line
/// content: they are reported through `flow_paused()`. A line longer than `max_line_chars` is
/// discarded up to its CR and reported as an RX overflow (ER2 2).
class Watlow942LineSplitter {
 public:
  explicit Watlow942LineSplitter(size_t max_line_chars = 64) : max_line_chars_(max_line_chars) {}

  struct Line {
    std::string text;
    bool overflowed = false;
  };

  /// Feeds one byte; returns a complete line when `byte` is the CR that ends one.
  std::optional<Line> Feed(uint8_t byte);
  /// Whether the peer's last flow-control byte was XOFF (stop sending).
  bool flow_paused() const { return flow_paused_; }

 private:
  size_t max_line_chars_;
  std::string line_;
  bool overflowed_ = false;
  bool flow_paused_ = false;
};

/// Formats a number as the 942 sends and accepts it: `decimals` places, at most 7 characters.
/// Returns nullopt when the value does not fit in 7 characters.
std::optional<std::string> FormatWatlow942Number(double value, int decimals);

/// Client side: `? MN d1 d2...<CR>` / `= MN d1 d2...<CR>` (data already formatted).
std::string EncodeWatlow942Request(Watlow942Command command,
                                   std::string_view mnemonic,
                                   const std::vector<std::string>& data = {});

/// Device side: the reply to a `?` line, `<XOFF><XON>fields joined by spaces<CR>`.
std::string EncodeWatlow942ReadReply(const std::vector<std::string>& fields);

/// Client side: the reply text of a `?` (the bytes between the XON and the CR), or nullopt when
/// `bytes` holds no complete reply yet.
std::optional<std::string> DecodeWatlow942ReadReply(std::string_view bytes);

}  // namespace adahrs::hil
