#include "hil/codecs/prologix.h"

#include <cctype>
#include <charconv>
#include <initializer_list>

namespace adahrs::hil {
namespace {

constexpr std::string_view kCrLf = "\r\n";

std::vector<std::string_view> Words(std::string_view text) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
    const size_t start = i;
    while (i < text.size() && text[i] != ' ' && text[i] != '\t') ++i;
    if (i > start) words.push_back(text.substr(start, i - start));
  }
  return words;
}

std::optional<int> IntIn(std::string_view word, int lo, int hi) {
  int value = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (ec != std::errc() || end != word.data() + word.size() || value < lo || value > hi)
    return std::nullopt;
  return value;
}

std::string Concat(std::initializer_list<std::string_view> parts) {
  std::string joined;
  for (const std::string_view part : parts) joined.append(part);
  return joined;
}

PrologixAction Reply(std::string text) {
  PrologixAction action;
  action.kind = PrologixAction::Kind::kReply;
  action.reply = std::move(text) + std::string(kCrLf);
  return action;
}

PrologixAction Ignored(std::string why) {
  PrologixAction action;
  action.kind = PrologixAction::Kind::kIgnored;
  action.reply = std::move(why);
  return action;
}

PrologixAction Of(PrologixAction::Kind kind) {
  PrologixAction action;
  action.kind = kind;
  return action;
}

}  // namespace

std::optional<PrologixLine> PrologixLineSplitter::Feed(uint8_t byte) {
  if (escaped_next_) {
    escaped_next_ = false;
    if (raw_.size() < 2) prefix_escaped_ = true;
    if (raw_.size() < max_line_chars_) raw_.push_back(static_cast<char>(byte));
    return std::nullopt;
  }
  if (byte == static_cast<uint8_t>(kPrologixEscape)) {
    escaped_next_ = true;
    return std::nullopt;
  }
  if (byte == '\r' || byte == '\n') {
    if (raw_.empty()) return std::nullopt;  // the LF of a CR LF pair, or an empty line
    PrologixLine line;
    // "++" is a command only when neither '+' was escaped (§7).
    line.is_command = !prefix_escaped_ && raw_.size() >= 2 && raw_[0] == '+' && raw_[1] == '+';
    line.text = line.is_command ? raw_.substr(2) : raw_;
    raw_.clear();
    prefix_escaped_ = false;
    return line;
  }
  if (raw_.size() < max_line_chars_) raw_.push_back(static_cast<char>(byte));
  return std::nullopt;
}

std::string EscapePrologixData(std::string_view data) {
  std::string escaped;
  for (const char c : data) {
    if (c == '\r' || c == '\n' || c == kPrologixEscape || c == '+')
      escaped.push_back(kPrologixEscape);
    escaped.push_back(c);
  }
  return escaped;
}

std::string_view PrologixEosTerminator(int eos) {
  switch (eos) {
    case 0:
      return "\r\n";
    case 1:
      return "\r";
    case 2:
      return "\n";
    default:
      return "";
  }
}

PrologixAction PrologixController::Apply(std::string_view command_text) {
  const std::vector<std::string_view> words = Words(command_text);
  if (words.empty()) return Ignored("empty command");
  std::string name;
  for (const char c : words[0])
    name.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  const size_t argc = words.size() - 1;
  PrologixSettings& s = settings_;
  // A 0/1 switch or a ranged integer setting: query without argument, set with one.
  auto setting = [&](int& value, int lo, int hi) -> PrologixAction {
    if (argc == 0) return Reply(std::to_string(value));
    const auto v = argc == 1 ? IntIn(words[1], lo, hi) : std::nullopt;
    if (!v) return Ignored(Concat({"++", name, ": argument out of range"}));
    value = *v;
    return Of(PrologixAction::Kind::kNone);
  };
  auto flag = [&](bool& value) -> PrologixAction {
    int v = value ? 1 : 0;
    PrologixAction action = setting(v, 0, 1);
    value = v == 1;
    return action;
  };
  if (name == "addr") {
    if (argc == 0) {
      const std::string pad = std::to_string(s.address);
      return Reply(s.secondary < 0 ? pad : Concat({pad, " ", std::to_string(s.secondary)}));
    }
    const auto pad = IntIn(words[1], 0, 30);
    const auto sad = argc == 2 ? IntIn(words[2], 96, 126) : std::nullopt;
    if (!pad || argc > 2 || (argc == 2 && !sad)) return Ignored("++addr: address out of range");
    s.address = *pad;
    s.secondary = sad ? *sad : -1;
    return Of(PrologixAction::Kind::kNone);
  }
  if (name == "auto") return flag(s.auto_read);
  if (name == "eoi") return flag(s.eoi);
  if (name == "eos") return setting(s.eos, 0, 3);
  if (name == "eot_enable") return flag(s.eot_enable);
  if (name == "eot_char") return setting(s.eot_char, 0, 255);
  if (name == "mode") return setting(s.mode, 0, 1);
  if (name == "read_tmo_ms") return setting(s.read_tmo_ms, 1, 3000);
  if (name == "savecfg") return flag(savecfg_);
  if (name == "ver") return Reply(version_text_);
  if (name == "read") {
    PrologixAction action = Of(PrologixAction::Kind::kRead);
    if (argc == 1 && words[1] == "eoi") {
      action.read_until_eoi = true;
    } else if (argc == 1) {
      const auto c = IntIn(words[1], 0, 255);
      if (!c) return Ignored("++read: expected eoi or a character code");
      action.read_until_char = *c;
    } else if (argc > 1) {
      return Ignored("++read: too many arguments");
    }
    return action;
  }
  if (name == "clr") return Of(PrologixAction::Kind::kDeviceClear);
  if (name == "trg") return Of(PrologixAction::Kind::kTrigger);
  if (name == "spoll") return Of(PrologixAction::Kind::kSerialPoll);
  if (name == "rst") return Of(PrologixAction::Kind::kReset);
  if (name == "ifc" || name == "loc" || name == "llo") return Of(PrologixAction::Kind::kNone);
  if (name == "srq") return Reply("0");  // no instrument here asserts SRQ
  return Ignored(Concat({"unrecognised command ++", name}));
}

}  // namespace adahrs::hil
