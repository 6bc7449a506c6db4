// The text name of a unit's serial number: "IMU-0001" / "ADS-0001" (four digits, zero padded),
// built from IDENTIFY's serial_number (docs/unit-protocol.md §6.2). The rig names its
// truth/<serial>.json files the same way and recordings use it in their `unit` column.
#pragma once

#include <cstdint>
#include <string>

#include "hil/station.h"

namespace adahrs::hil {

/// "IMU-%04u" or "ADS-%04u" of `serial_number`.
std::string UnitSerialText(UnitKind kind, uint32_t serial_number);

}  // namespace adahrs::hil
