// A crash while a row was being written leaves a CSV whose last line has no newline. Before a
// resumed run appends to such a file, the torn bytes are moved aside to `<csv>.torn-<n>` (kept,
// never silently dropped) and the CSV is cut back to its last complete line, so the appended rows
// start on a line of their own. A compressed CSV (`.csv.gz`) torn by a crash ends inside a gzip
// member: the bytes after the last complete member are moved aside the same way and the file is
// cut back to that member's end, so the appended members follow a complete one. Finding that end
// decompresses the whole file (about a second per 100 MB compressed on a 2-core machine; a resume
// does it once). Leaves deciding what to journal to the caller.
#pragma once

#include <filesystem>
#include <optional>

namespace adahrs::hil {

/// If `csv_path` does not end with '\n' (compressed: with a complete gzip member), writes the bytes
/// after its last newline (last complete member) to
/// `<csv_path>.torn-<n>` (n the smallest unused number from 1, fsync'd) and truncates the CSV after
/// that newline; returns the torn file's path. Returns nullopt when the file ends cleanly, is empty
/// or does not exist. Throws std::runtime_error naming the path on an I/O failure.
std::optional<std::filesystem::path> SetAsideTornTail(const std::filesystem::path& csv_path);

}  // namespace adahrs::hil
