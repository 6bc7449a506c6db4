// The run's append-only journal, `journal.jsonl` in the run directory: one JSON object per line,
// each with "event" and the pipeline clock time "t_s" (docs/executor.md lists the events: run
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
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace adahrs::calib {

inline constexpr const char* kJournalName = "journal.jsonl";

class JournalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Journal {
 public:
  /// Opens (creating if needed) `run_dir`/journal.jsonl for appending. Throws JournalError naming
  /// the path when it cannot.
  explicit Journal(const std::filesystem::path& run_dir);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  /// Appends `event` (an object that has "event") as one line and flushes it to the kernel.
  void Append(const nlohmann::json& event);
  /// Flushes and fsyncs the journal: everything appended so far survives a crash.
  void Sync();

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
};

struct JournalContents {
  std::vector<nlohmann::json> events;
  int torn_lines = 0;  ///< 1 when the last line was incomplete (a crash mid-write), else 0
};

/// Reads `run_dir`/journal.jsonl. Throws JournalError naming the file and line for a missing
/// file, or a complete line that is not a JSON object with a string "event".
JournalContents ReadJournal(const std::filesystem::path& run_dir);

}  // namespace adahrs::calib
