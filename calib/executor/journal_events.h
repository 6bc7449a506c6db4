// The events of a run's journal (journal.h, docs/executor.md "Journal"), one struct each, and their
// JSON lines: {"event": <name>, "t_s": <pipeline clock>, ...the struct's fields}. Steps and action
// indices are indices into the run's sequence and execution plan; times are pipeline clock seconds.
// Reading refuses an unknown event, a missing field or a field of the wrong type, naming the
// field; whether a step or a time fits the run is the reader's caller's question (resume_point.h).
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

namespace adahrs::calib {

class JournalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// "run_started", or "run_resumed" when `resumed`.
struct RunStarted {
  double t_s = 0.0;
  std::string utc;  ///< ISO 8601 wall-clock time of the start
  size_t first_step = 0;
  bool resumed = false;
};
/// A torn last line of a recording file or the journal moved aside before a resume.
struct TornTailSetAside {
  double t_s = 0.0;
  std::string file;
  std::string moved_to;
};
/// The rig made safe before anything else; the table's rate as found, when there is a table.
struct RigSafeAtStart {
  double t_s = 0.0;
  std::optional<double> table_found_dps;
};
/// A partial step begun again on resume; its earlier rows are rejected from this time on.
struct StepRepeated {
  double t_s = 0.0;
  size_t step = 0;
  double first_attempt_t_start_s = 0.0;
};
struct ActionStarted {
  double t_s = 0.0;
  size_t index = 0;  ///< in the execution plan
  size_t step = 0;
  std::string action;  ///< its description
};
struct ActionCompleted {
  double t_s = 0.0;
  size_t index = 0;
  size_t step = 0;
};
struct StepCompleted {
  double t_s = 0.0;
  size_t step = 0;
};
struct InterlockFailed {
  double t_s = 0.0;  ///< end of the rejected interval
  size_t step = 0;
  std::string interlock;  ///< "gravity", "gyro axis", ...
  int attempt = 0;
  std::vector<std::string> units;  ///< one line per failing unit: serial and what it measured
};
struct StateRestored {
  double t_s = 0.0;
};
struct SafeStopFailed {
  double t_s = 0.0;
  std::string what;  ///< "table stop", ...
  std::string reason;
};
struct RigSafe {
  double t_s = 0.0;
};
/// "interrupted" (a stop request or a signal), or "aborted" (an error) when `aborted`.
struct RunStopped {
  double t_s = 0.0;
  size_t action = 0;  ///< plan index of the action under way
  std::string reason;
  bool aborted = false;
};
struct RunCompleted {
  double t_s = 0.0;
};

using JournalEvent = std::variant<RunStarted,
                                  TornTailSetAside,
                                  RigSafeAtStart,
                                  StepRepeated,
                                  ActionStarted,
                                  ActionCompleted,
                                  StepCompleted,
                                  InterlockFailed,
                                  StateRestored,
                                  SafeStopFailed,
                                  RigSafe,
                                  RunStopped,
                                  RunCompleted>;

/// The event's name as the journal spells it ("run_started", "step_completed", ...).
std::string EventName(const JournalEvent& event);
double EventTimeS(const JournalEvent& event);
/// The step an event is about, for the events that name one.
std::optional<size_t> EventStep(const JournalEvent& event);

nlohmann::json ToJson(const JournalEvent& event);
/// Throws JournalError "<where>: <event>: <what is wrong>".
JournalEvent JournalEventFromJson(const nlohmann::json& line, const std::string& where);

}  // namespace adahrs::calib
