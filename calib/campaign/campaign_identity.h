// The identity stage of a campaign: before anything moves, each unit of a station is asked for its
// serial (IDENTIFY over its port, hil/drivers/unit_link.h; the text as hil/drivers/unit_serial.h
// writes it, e.g. "IMU-000123") and the serial is compared with the one the campaign file expects
// for that unit role. A unit giving another serial (a unit mounted on the wrong port, a swapped
// cable) is refused: its slot is left out of every stage, the others go on. Units with no expected
// serial are not asked. The station the runs then use, without the refused units, is written as
// `<dir>/<original file name>` (Station::ToJson) so that the runs' meta.json names it.
// Errors: an expected role that no station has is refused before any port is opened; a unit that
// does not answer IDENTIFY throws as the driver does (naming the role and port).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "hil/station.h"

namespace adahrs::calib {

struct IdentityCheck {
  hil::Station station;              ///< the station without the refused units
  std::vector<std::string> refused;  ///< one message per refused unit
};

/// Asks every unit of `station` with an expected serial for its own.
IdentityCheck CheckUnitIdentities(const hil::Station& station,
                                  const std::map<std::string, std::string>& expected);

/// Writes `station` to `dir`/`original`'s file name; returns the path written.
std::string WriteCheckedStation(const hil::Station& station,
                                const std::filesystem::path& dir,
                                const std::filesystem::path& original);

/// Throws common::ParamError if `expected` names a role that neither station file has (an empty
/// file name is an absent station).
void RequireExpectedRolesExist(const std::map<std::string, std::string>& expected,
                               const std::string& imu_station_file,
                               const std::string& ads_station_file);

}  // namespace adahrs::calib
