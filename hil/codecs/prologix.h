// The Prologix GPIB-USB controller's host-side line protocol (shared/protocols.md §6; DOC:
// Prologix GPIB-USB Controller User Manual v6.107, §7 data transmission and §8 commands).
//
// Host bytes are cut into lines at an un-escaped CR or LF (§7). A line that starts with an
// un-escaped `++` is a command to the adapter (§8); any other line is data for the instrument at
// `++addr`, with ESC-escaped CR, LF, ESC and `+` restored (§7.1). The settings the commands set
// (mode, addr, auto, eoi, eos, eot, read_tmo_ms) and the answers to queries are kept here, pure
// and without time: PrologixController::Apply returns what the adapter must do next (reply text,
// read from the instrument, device clear …) and the device model (rig_sim) does it on the clock.
// Replies to `++` queries end in CR LF (INF). Unknown commands and out-of-range arguments are
// ignored and reported as such (INF: the manual does not say what the adapter answers).
// Not here: DEVICE-mode listening/talking, `++lon`, `++status` (device mode only), `++help` text.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace adahrs::hil {

inline constexpr char kPrologixEscape = 0x1B;

struct PrologixLine {
  bool is_command = false;  ///< began with an un-escaped "++"
  std::string text;         ///< command text after "++", or the un-escaped data payload
};

/// Splits host bytes into lines. Lines longer than `max_line_chars` are truncated there (the
/// adapter's buffer is finite; INF) and flagged.
class PrologixLineSplitter {
 public:
  explicit PrologixLineSplitter(size_t max_line_chars = 256) : max_line_chars_(max_line_chars) {}
  /// Feeds one byte; returns a line when `byte` is the un-escaped CR or LF ending a non-empty one.
  std::optional<PrologixLine> Feed(uint8_t byte);

 private:
  size_t max_line_chars_;
  std::string raw_;  // the line so far, escapes removed
  bool escaped_next_ = false;
  bool prefix_escaped_ = false;  // one of the first two bytes was escaped
};

/// Client side: escapes CR, LF, ESC and '+' in data for the instrument (§7.1).
std::string EscapePrologixData(std::string_view data);

/// The GPIB terminator appended to data per `++eos` (0 CR LF, 1 CR, 2 LF, 3 none; §8.5).
std::string_view PrologixEosTerminator(int eos);

struct PrologixSettings {
  int mode = 1;             ///< 1 CONTROLLER, 0 DEVICE (§8.12)
  int address = 0;          ///< primary GPIB address 0-30 (§8.1)
  int secondary = -1;       ///< 96-126, or -1 when none
  bool auto_read = false;   ///< read-after-write (§8.2)
  bool eoi = true;          ///< assert EOI with the last byte sent (§8.4)
  int eos = 0;              ///< §8.5
  bool eot_enable = false;  ///< append eot_char when EOI is seen (§8.6)
  int eot_char = 0;         ///< §8.7
  int read_tmo_ms = 500;    ///< 1-3000 (§8.14)
};

/// What the adapter must do after a command.
struct PrologixAction {
  enum class Kind {
    kNone,         ///< settings changed (or nothing to do)
    kReply,        ///< send `reply` to the host
    kRead,         ///< address the instrument to talk and pass its bytes to the host
    kDeviceClear,  ///< ++clr: selected device clear
    kTrigger,      ///< ++trg
    kSerialPoll,   ///< ++spoll: reply with the instrument's status byte
    kReset,        ///< ++rst: the adapter restarts with its saved settings
    kIgnored,      ///< unknown command or bad argument; `reply` says why (for the log only)
  };
  Kind kind = Kind::kNone;
  std::string reply;
  bool read_until_eoi = false;  ///< kRead: stop at EOI
  int read_until_char = -1;     ///< kRead: stop at this character (0-255), −1 none
};

/// The adapter's `++` command interpreter over its settings.
class PrologixController {
 public:
  explicit PrologixController(std::string version_text, PrologixSettings defaults = {})
      : version_text_(std::move(version_text)), defaults_(defaults), settings_(defaults) {}

  /// Interprets the text after "++" of one command line.
  PrologixAction Apply(std::string_view command_text);

  const PrologixSettings& settings() const { return settings_; }
  /// After ++rst: the settings as saved (with `++savecfg 1` every change is saved, §8.16),
  /// otherwise the power-up defaults.
  void Reset() {
    if (!savecfg_) settings_ = defaults_;
  }

 private:
  std::string version_text_;
  PrologixSettings defaults_;
  PrologixSettings settings_;
  bool savecfg_ = true;
};

}  // namespace adahrs::hil
