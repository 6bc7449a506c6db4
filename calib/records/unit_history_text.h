// The text `adahrs units show SERIAL` prints: a unit's runs, constants versions (with download
// and commit state, and the constants version/CRC the unit reported) and acceptance verdicts
// (failed points listed), oldest first. Plain fixed-width text for a terminal.
#pragma once

#include <string>

#include "calib/records/records_store.h"

namespace adahrs::calib {

std::string FormatUnitHistory(const UnitHistory& history);

}  // namespace adahrs::calib
