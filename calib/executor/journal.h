// The run's append-only journal, `journal.jsonl` in the run directory: one JSON object per line,
// each with "event" and the pipeline clock time "t_s" (journal_events.h; docs/executor.md: run
// started/resumed, action started/completed with its index, step completed, interlock failures,
// torn rows set aside, aborts and interruptions, run completed). It is what a resume reads to
// find where the run stopped. Every line is flushed to the kernel as it is appended (a killed
// process loses nothing); Sync() also fsyncs (a power loss loses nothing), which the executor
// does at every step boundary and before it ends.
// Reading tolerates a torn last line (a crash mid-write): it is counted, not parsed. A bad line
// anywhere else is an error naming the file and the line.
// Left out: rotation, concurrent writers (one executor owns a run directory).
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "calib/executor/journal_events.h"

namespace adahrs::calib {

inline constexpr const char* kJournalName = "journal.jsonl";

class Journal {
 public:
  /// Opens (creating if needed) `run_dir`/journal.jsonl for appending. Throws JournalError naming
  /// the path when it cannot.
  explicit Journal(const std::filesystem::path& run_dir);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  /// Appends `event` as one line and flushes it to the kernel.
  void Append(const JournalEvent& event);
  /// Flushes and fsyncs the journal: everything appended so far survives a crash.
  void Sync();

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
};

struct JournalContents {
  std::vector<JournalEvent> events;
  int torn_lines = 0;  ///< 1 when the last line was incomplete (a crash mid-write), else 0
};

/// Reads `run_dir`/journal.jsonl. Throws JournalError naming the file and line for a missing
/// file, or a complete line that is not one of the events (journal_events.h).
JournalContents ReadJournal(const std::filesystem::path& run_dir);

}  // namespace adahrs::calib
