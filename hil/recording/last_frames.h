// The latest packet of every unit in an existing CSV of the recording format (plain or
// compressed), so a writer appending to it (a resumed run) continues each unit's frame count
// (frame_count.h) where the file left it. One pass over the file's lines; cells other than the
// unit, seq, t_s and frame columns are not parsed.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "hil/recording/frame_count.h"

namespace adahrs::hil {

/// Per unit serial, its last complete row's frame, seq and t_s; empty when the file has no rows
/// or no frame column (a version before 3). Throws std::runtime_error naming the file, line and
/// column for a cell that is not a number of its column.
std::map<std::string, FrameState> LastFrames(const std::filesystem::path& csv_path);

}  // namespace adahrs::hil
