// Where a run stopped, read from its journal (journal.h): the first sequence step not completed
// (steps complete in order), when that step first began (its rows from before the resume are a
// "repeated partial step" and get a rejected interval), and the latest journal time, from which
// the pipeline clock continues.
// Left out: the recording itself (the caller also takes the latest t_s of the CSVs into account).
#pragma once

#include <cstddef>
#include <optional>

#include "calib/executor/journal.h"

namespace adahrs::calib {

struct ResumePoint {
  size_t first_incomplete_step = 0;  ///< == the step count when every step completed
  /// t_s at which the first incomplete step's first action started, if it ever started.
  std::optional<double> interrupted_step_started_s;
  double last_t_s = 0.0;  ///< latest "t_s" in the journal
  bool run_completed = false;
};

/// Reads the resume point from a journal of a sequence of `step_count` steps. Throws JournalError
/// when the journal has no "run_started" event or an event lacks a numeric t_s or step.
ResumePoint FindResumePoint(const JournalContents& journal, size_t step_count);

}  // namespace adahrs::calib
