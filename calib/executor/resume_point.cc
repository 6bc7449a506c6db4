#include "calib/executor/resume_point.h"

#include <algorithm>
#include <string>
#include <vector>

namespace adahrs::calib {
namespace {

// A run lasting longer than this is not a run: a time beyond it is a corrupt journal (1e308 once
// set the resumed clock so far ahead that the resume waited forever).
constexpr double kMaxRunTime_s = 365.0 * 86400.0;

std::string Where(const nlohmann::json& event, size_t index) {
  return "journal event " + std::to_string(index + 1) + " (" + event["event"].get<std::string>() +
         ")";
}

double NumberOf(const nlohmann::json& event, const char* key, size_t index) {
  if (!event.contains(key) || !event[key].is_number()) {
    throw JournalError(Where(event, index) + ": \"" + key + "\" missing or not a number");
  }
  return event[key].get<double>();
}

// The event's time: finite, within a year of the run's start, never before the previous event's.
double TimeOf(const nlohmann::json& event, size_t index, double previous_s) {
  const double t_s = NumberOf(event, "t_s", index);
  if (!(t_s >= 0.0 && t_s <= kMaxRunTime_s)) {
    throw JournalError(Where(event, index) + ": t_s " + event["t_s"].dump() +
                       " is not a time of a run (0 ... 1 year)");
  }
  if (t_s < previous_s) {
    throw JournalError(Where(event, index) + ": t_s " + event["t_s"].dump() +
                       " is before the previous event's");
  }
  return t_s;
}

// The event's step: an integer index of the sequence.
size_t StepOf(const nlohmann::json& event, size_t index, size_t step_count) {
  if (!event.contains("step") || !event["step"].is_number_integer() ||
      event["step"].get<int64_t>() < 0 ||
      event["step"].get<int64_t>() >= static_cast<int64_t>(step_count)) {
    throw JournalError(Where(event, index) + ": \"step\" " +
                       (event.contains("step") ? event["step"].dump() : "missing") +
                       " is not a step of the sequence (0 ... " + std::to_string(step_count - 1) +
                       ")");
  }
  return static_cast<size_t>(event["step"].get<int64_t>());
}

}  // namespace

ResumePoint FindResumePoint(const JournalContents& journal, size_t step_count) {
  ResumePoint point;
  std::vector<bool> completed(step_count, false);
  bool started = false;
  for (size_t i = 0; i < journal.events.size(); ++i) {
    const nlohmann::json& e = journal.events[i];
    const std::string kind = e["event"].get<std::string>();
    point.last_t_s = TimeOf(e, i, point.last_t_s);
    if (kind == "run_started") started = true;
    if (kind == "run_completed") point.run_completed = true;
    if (kind == "step_completed") completed[StepOf(e, i, step_count)] = true;
  }
  if (!started) throw JournalError("journal has no run_started event: not a run directory?");
  point.first_incomplete_step =
      static_cast<size_t>(std::find(completed.begin(), completed.end(), false) - completed.begin());
  for (size_t i = 0; i < journal.events.size(); ++i) {
    const nlohmann::json& e = journal.events[i];
    if (e["event"] == "action_started" && StepOf(e, i, step_count) == point.first_incomplete_step) {
      point.interrupted_step_started_s = NumberOf(e, "t_s", i);
      break;
    }
  }
  return point;
}

}  // namespace adahrs::calib
