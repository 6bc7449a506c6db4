#include "calib/executor/resume_point.h"

#include <algorithm>
#include <string>
#include <vector>

namespace adahrs::calib {
namespace {

double NumberOf(const nlohmann::json& event, const char* key, size_t index) {
  if (!event.contains(key) || !event[key].is_number()) {
    throw JournalError("journal event " + std::to_string(index + 1) + " (" +
                       event["event"].get<std::string>() + "): \"" + key +
                       "\" missing or not a number");
  }
  return event[key].get<double>();
}

}  // namespace

ResumePoint FindResumePoint(const JournalContents& journal, size_t step_count) {
  ResumePoint point;
  std::vector<bool> completed(step_count, false);
  bool started = false;
  for (size_t i = 0; i < journal.events.size(); ++i) {
    const nlohmann::json& e = journal.events[i];
    const std::string kind = e["event"].get<std::string>();
    point.last_t_s = std::max(point.last_t_s, NumberOf(e, "t_s", i));
    if (kind == "run_started") started = true;
    if (kind == "run_completed") point.run_completed = true;
    if (kind == "step_completed") {
      const auto step = static_cast<size_t>(NumberOf(e, "step", i));
      if (step < step_count) completed[step] = true;
    }
  }
  if (!started) throw JournalError("journal has no run_started event: not a run directory?");
  point.first_incomplete_step =
      static_cast<size_t>(std::find(completed.begin(), completed.end(), false) - completed.begin());
  for (size_t i = 0; i < journal.events.size(); ++i) {
    const nlohmann::json& e = journal.events[i];
    if (e["event"] == "action_started" &&
        static_cast<size_t>(NumberOf(e, "step", i)) == point.first_incomplete_step) {
      point.interrupted_step_started_s = NumberOf(e, "t_s", i);
      break;
    }
  }
  return point;
}

}  // namespace adahrs::calib
