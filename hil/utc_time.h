// The wall clock's present time as text, for the records a run leaves (meta.json, constants
// files, the records database): ISO 8601 in UTC to the second, "2026-11-27T12:30:05Z".
#pragma once

#include <string>

namespace adahrs::hil {

std::string UtcNowIso8601();

}  // namespace adahrs::hil
