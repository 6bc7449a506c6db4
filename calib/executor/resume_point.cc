#include "calib/executor/resume_point.h"

#include <algorithm>
#include <string>
#include <vector>

namespace adahrs::calib {
namespace {

// A run lasting longer than this is not a run: a time beyond it is a corrupt journal (1e308 once
// set the resumed clock so far ahead that the resume waited forever).
constexpr double kMaxRunTime_s = 365.0 * 86400.0;

std::string Where(const JournalEvent& event, size_t index) {
  return "journal event " + std::to_string(index + 1) + " (" + EventName(event) + ")";
}

// The event's time: finite, within a year of the run's start, never before the previous event's.
double TimeOf(const JournalEvent& event, size_t index, double previous_s) {
  const double t_s = EventTimeS(event);
  if (!(t_s >= 0.0 && t_s <= kMaxRunTime_s)) {
    throw JournalError(Where(event, index) + ": t_s " + nlohmann::json(t_s).dump() +
                       " is not a time of a run (0 ... 1 year)");
  }
  if (t_s < previous_s) {
    throw JournalError(Where(event, index) + ": t_s " + nlohmann::json(t_s).dump() +
                       " is before the previous event's");
  }
  return t_s;
}

// The event's step, if it names one: an index of the sequence.
void CheckStep(const JournalEvent& event, size_t index, size_t step_count) {
  const std::optional<size_t> step = EventStep(event);
  if (step && *step >= step_count) {
    throw JournalError(Where(event, index) + ": \"step\" " + std::to_string(*step) +
                       " is not a step of the sequence (0 ... " + std::to_string(step_count - 1) +
                       ")");
  }
}

}  // namespace

ResumePoint FindResumePoint(const JournalContents& journal, size_t step_count) {
  ResumePoint point;
  std::vector<bool> completed(step_count, false);
  bool started = false;
  for (size_t i = 0; i < journal.events.size(); ++i) {
    const JournalEvent& e = journal.events[i];
    point.last_t_s = TimeOf(e, i, point.last_t_s);
    CheckStep(e, i, step_count);
    if (const auto* s = std::get_if<RunStarted>(&e); s != nullptr && !s->resumed) started = true;
    if (std::holds_alternative<RunCompleted>(e)) point.run_completed = true;
    if (const auto* s = std::get_if<StepCompleted>(&e)) completed[s->step] = true;
  }
  if (!started) throw JournalError("journal has no run_started event: not a run directory?");
  point.first_incomplete_step =
      static_cast<size_t>(std::find(completed.begin(), completed.end(), false) - completed.begin());
  for (const JournalEvent& e : journal.events) {
    const auto* a = std::get_if<ActionStarted>(&e);
    if (a != nullptr && a->step == point.first_incomplete_step) {
      point.interrupted_step_started_s = a->t_s;
      break;
    }
  }
  return point;
}

}  // namespace adahrs::calib
