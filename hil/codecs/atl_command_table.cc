#include "hil/codecs/atl_command_table.h"

#include <cmath>
#include <set>

#include "common/param_reader.h"

namespace adahrs::hil {
namespace {

using common::ParamReader;

// The widest argument limits a table may declare; beyond them a number means a typo.
constexpr double kLimitBound = 1e9;

std::string Confidence(const ParamReader& r) {
  static const std::set<std::string> kLabels{"DOC", "DRV", "INF", "UNKNOWN"};
  const std::string label = r.String("confidence");
  if (!kLabels.count(label)) {
    r.Fail(r.path() + ".confidence",
           "\"" + label + "\" is not one of DOC, DRV, INF, UNKNOWN (shared/protocols.md)");
  }
  return label;
}

AtlForm ReadForm(const ParamReader& r, bool is_query, const std::string& entry_confidence) {
  AtlForm form;
  form.confidence = is_query ? Confidence(r) : entry_confidence;
  if (is_query) {
    form.argument = AtlArgument::kNone;
  } else {
    const std::string type = r.String("argument");
    if (type == "none") {
      form.argument = AtlArgument::kNone;
    } else if (type == "integer") {
      form.argument = AtlArgument::kInteger;
    } else if (type == "real") {
      form.argument = AtlArgument::kReal;
    } else {
      r.Fail(r.path() + ".argument", "\"" + type + "\" is not one of none, integer, real");
    }
  }
  if (form.argument != AtlArgument::kNone) {
    form.unit = r.String("unit");
    form.min = r.Number("min", -kLimitBound, kLimitBound, form.unit);
    form.max = r.Number("max", -kLimitBound, kLimitBound, form.unit);
    if (form.min > form.max) r.Fail(r.path() + ".max", "max is below min");
    if (form.argument == AtlArgument::kInteger &&
        (std::floor(form.min) != form.min || std::floor(form.max) != form.max)) {
      r.Fail(r.path() + ".min", "limits of an integer argument must be integers");
    }
  }
  if (is_query || r.Has("reply")) {
    form.reply = r.String("reply");
    if (form.reply.find("{value}") == std::string::npos) {
      r.Fail(r.path() + ".reply", "reply template \"" + form.reply + "\" has no {value}");
    }
    form.decimals = static_cast<int>(r.Integer("decimals", 0, 9));
  }
  r.ExpectAllKeysUsed();
  return form;
}

AtlCommandSpec ReadCommand(const ParamReader& r) {
  AtlCommandSpec spec;
  spec.mnemonic = r.String("mnemonic");
  if (spec.mnemonic.empty() || spec.mnemonic.size() > 8) {
    r.Fail(r.path() + ".mnemonic", "a mnemonic has 1 to 8 letters");
  }
  for (char c : spec.mnemonic) {
    if (c < 'A' || c > 'Z') {
      r.Fail(r.path() + ".mnemonic",
             "\"" + spec.mnemonic + "\": a mnemonic is upper-case letters only");
    }
  }
  spec.operation = r.String("operation");
  spec.confidence = Confidence(r);
  spec.meaning = r.String("meaning");
  if (r.Has("action")) spec.action = ReadForm(r.Child("action"), false, spec.confidence);
  if (r.Has("query")) spec.query = ReadForm(r.Child("query"), true, spec.confidence);
  if (!spec.action && !spec.query) {
    r.Fail(r.path(), "command " + spec.mnemonic + " has neither an action nor a query form");
  }
  r.ExpectAllKeysUsed();
  return spec;
}

}  // namespace

AtlCommandTable AtlCommandTable::Load(const std::string& file_path) {
  return FromJson(ParamReader::LoadFile(file_path), file_path);
}

AtlCommandTable AtlCommandTable::FromJson(const nlohmann::json& table, const std::string& source) {
  const ParamReader r(table, source);
  AtlCommandTable out;
  const std::string format = r.String("format");
  if (format != "adahrs-atl-command-table-1") {
    r.Fail("$.format", "\"" + format + "\" is not adahrs-atl-command-table-1");
  }
  r.String("about");

  const ParamReader framing = r.Child("framing");
  out.framing_.confidence = Confidence(framing);
  framing.String("note");
  out.framing_.line_end = framing.String("line_end");
  out.framing_.prompt = framing.String("prompt");
  if (out.framing_.line_end.empty()) framing.Fail("$.framing.line_end", "must not be empty");
  out.framing_.echo = framing.Flag("echo");
  out.framing_.max_line_chars = static_cast<size_t>(framing.Integer("max_line_chars", 8, 4096));
  framing.ExpectAllKeysUsed();

  const ParamReader errors = r.Child("errors");
  out.errors_.confidence = Confidence(errors);
  errors.String("note");
  out.errors_.unknown_command = errors.String("unknown_command");
  out.errors_.bad_argument = errors.String("bad_argument");
  out.errors_.out_of_range = errors.String("out_of_range");
  out.errors_.servo_off = errors.String("servo_off");
  out.errors_.interlock_open = errors.String("interlock_open");
  out.errors_.line_too_long = errors.String("line_too_long");
  errors.ExpectAllKeysUsed();

  const auto commands = table.find("commands");
  if (commands == table.end() || !commands->is_array() || commands->empty()) {
    r.Fail("$.commands", "expected a non-empty array of command objects");
  }
  std::set<std::string> seen;
  for (size_t i = 0; i < commands->size(); ++i) {
    const ParamReader entry = r.Element("commands", i, commands->size());
    AtlCommandSpec spec = ReadCommand(entry);
    if (!seen.insert(spec.mnemonic).second) {
      entry.Fail(entry.path() + ".mnemonic", "duplicate mnemonic " + spec.mnemonic);
    }
    out.commands_.push_back(std::move(spec));
  }
  r.ExpectAllKeysUsed();
  return out;
}

const AtlCommandSpec* AtlCommandTable::Find(std::string_view mnemonic) const {
  for (const AtlCommandSpec& spec : commands_) {
    if (spec.mnemonic == mnemonic) return &spec;
  }
  return nullptr;
}

const AtlCommandSpec* AtlCommandTable::FindOperation(std::string_view operation) const {
  for (const AtlCommandSpec& spec : commands_) {
    if (spec.operation == operation) return &spec;
  }
  return nullptr;
}

}  // namespace adahrs::hil
