#include "calib/executor/journal_events.h"

#include <cstdint>
#include <limits>

#include "common/param_reader.h"
#include "common/printable_text.h"

namespace adahrs::calib {
namespace {

using nlohmann::json;

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

// The fields of one journal line, read strictly (common::ParamReader: a missing field or one of the
// wrong type is refused naming the line, the event and the field).
class Fields {
 public:
  Fields(const json& line, const std::string& where) : line_(line), reader_(line, where) {}

  double Number(const char* key) const { return reader_.Number(key, -kAny, kAny, "s"); }
  size_t Index(const char* key) const {
    return static_cast<size_t>(reader_.Integer(key, 0, INT64_MAX));
  }
  int Integer(const char* key) const {
    return static_cast<int>(reader_.Integer(key, INT32_MIN, INT32_MAX));
  }
  std::string String(const char* key) const { return reader_.String(key); }
  std::vector<std::string> Strings(const char* key) const {
    std::vector<std::string> out;
    const json& v = line_.contains(key) ? line_.at(key) : json();
    if (!v.is_array()) reader_.Fail(std::string("$.") + key, "expected an array of strings");
    for (const json& item : v) {
      if (!item.is_string()) reader_.Fail(std::string("$.") + key, "expected an array of strings");
      out.push_back(item.get<std::string>());
    }
    return out;
  }
  std::optional<double> OptionalNumber(const char* key) const {
    return reader_.Has(key) ? std::optional<double>(Number(key)) : std::nullopt;
  }

 private:
  static constexpr double kAny = std::numeric_limits<double>::max();
  const json& line_;
  common::ParamReader reader_;
};

// The event `name` from its fields; nullopt for a name that is no event of this journal.
std::optional<JournalEvent> Parse(const std::string& name, const Fields& f) {
  const double t_s = f.Number("t_s");
  if (name == "run_started" || name == "run_resumed") {
    return RunStarted{t_s, f.String("utc"), f.Index("first_step"), name == "run_resumed"};
  }
  if (name == "torn_tail_set_aside") {
    return TornTailSetAside{t_s, f.String("file"), f.String("moved_to")};
  }
  if (name == "rig_safe_at_start") return RigSafeAtStart{t_s, f.OptionalNumber("table_found_dps")};
  if (name == "step_repeated") {
    return StepRepeated{t_s, f.Index("step"), f.Number("first_attempt_t_start_s")};
  }
  if (name == "action_started") {
    return ActionStarted{t_s, f.Index("index"), f.Index("step"), f.String("action")};
  }
  if (name == "action_completed") return ActionCompleted{t_s, f.Index("index"), f.Index("step")};
  if (name == "step_completed") return StepCompleted{t_s, f.Index("step")};
  if (name == "interlock_failed") {
    return InterlockFailed{
        t_s, f.Index("step"), f.String("interlock"), f.Integer("attempt"), f.Strings("units")};
  }
  if (name == "state_restored") return StateRestored{t_s};
  if (name == "safe_stop_failed") return SafeStopFailed{t_s, f.String("what"), f.String("reason")};
  if (name == "rig_safe") return RigSafe{t_s};
  if (name == "interrupted" || name == "aborted") {
    return RunStopped{t_s, f.Index("action"), f.String("reason"), name == "aborted"};
  }
  if (name == "run_completed") return RunCompleted{t_s};
  return std::nullopt;
}

}  // namespace

std::string EventName(const JournalEvent& event) {
  return std::visit(
      Overloaded{
          [](const RunStarted& e) -> std::string {
            return e.resumed ? "run_resumed" : "run_started";
          },
          [](const TornTailSetAside&) -> std::string { return "torn_tail_set_aside"; },
          [](const RigSafeAtStart&) -> std::string { return "rig_safe_at_start"; },
          [](const StepRepeated&) -> std::string { return "step_repeated"; },
          [](const ActionStarted&) -> std::string { return "action_started"; },
          [](const ActionCompleted&) -> std::string { return "action_completed"; },
          [](const StepCompleted&) -> std::string { return "step_completed"; },
          [](const InterlockFailed&) -> std::string { return "interlock_failed"; },
          [](const StateRestored&) -> std::string { return "state_restored"; },
          [](const SafeStopFailed&) -> std::string { return "safe_stop_failed"; },
          [](const RigSafe&) -> std::string { return "rig_safe"; },
          [](const RunStopped& e) -> std::string { return e.aborted ? "aborted" : "interrupted"; },
          [](const RunCompleted&) -> std::string { return "run_completed"; }},
      event);
}

double EventTimeS(const JournalEvent& event) {
  return std::visit([](const auto& e) { return e.t_s; }, event);
}

std::optional<size_t> EventStep(const JournalEvent& event) {
  return std::visit(
      [](const auto& e) -> std::optional<size_t> {
        if constexpr (requires { e.step; }) {
          return e.step;
        } else {
          return std::nullopt;
        }
      },
      event);
}

json ToJson(const JournalEvent& event) {
  json j = {{"event", EventName(event)}, {"t_s", EventTimeS(event)}};
  std::visit(Overloaded{[&](const RunStarted& e) {
                          j["utc"] = e.utc;
                          j["first_step"] = e.first_step;
                        },
                        [&](const TornTailSetAside& e) {
                          j["file"] = e.file;
                          j["moved_to"] = e.moved_to;
                        },
                        [&](const RigSafeAtStart& e) {
                          if (e.table_found_dps) j["table_found_dps"] = *e.table_found_dps;
                        },
                        [&](const StepRepeated& e) {
                          j["step"] = e.step;
                          j["first_attempt_t_start_s"] = e.first_attempt_t_start_s;
                        },
                        [&](const ActionStarted& e) {
                          j["index"] = e.index;
                          j["step"] = e.step;
                          j["action"] = e.action;
                        },
                        [&](const ActionCompleted& e) {
                          j["index"] = e.index;
                          j["step"] = e.step;
                        },
                        [&](const StepCompleted& e) { j["step"] = e.step; },
                        [&](const InterlockFailed& e) {
                          j["step"] = e.step;
                          j["interlock"] = e.interlock;
                          j["attempt"] = e.attempt;
                          j["units"] = e.units;
                        },
                        [&](const SafeStopFailed& e) {
                          j["what"] = e.what;
                          j["reason"] = e.reason;
                        },
                        [&](const RunStopped& e) {
                          j["action"] = e.action;
                          j["reason"] = e.reason;
                        },
                        [](const auto&) {}},
             event);
  return j;
}

JournalEvent JournalEventFromJson(const json& line, const std::string& where) {
  if (!line.is_object() || !line.contains("event") || !line["event"].is_string()) {
    throw JournalError(where + ": not an object with a string \"event\"");
  }
  const std::string name = line["event"].get<std::string>();
  const std::string at = where + ": " + common::PrintableText(name);
  std::optional<JournalEvent> event;
  try {
    event = Parse(name, Fields(line, at));
  } catch (const common::ParamError& e) {
    throw JournalError(e.what());
  }
  if (!event) throw JournalError(at + ": not an event of this journal (docs/executor.md)");
  return *event;
}

}  // namespace adahrs::calib
