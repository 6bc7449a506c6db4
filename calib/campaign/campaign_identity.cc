#include "calib/campaign/campaign_identity.h"

#include <memory>
#include <set>

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "hil/clock.h"
#include "hil/drivers/unit_link.h"
#include "hil/drivers/unit_serial.h"

namespace adahrs::calib {

IdentityCheck CheckUnitIdentities(const hil::Station& station,
                                  const std::map<std::string, std::string>& expected) {
  IdentityCheck check{station, {}};
  check.station.units.clear();
  std::unique_ptr<hil::Clock> clock;
  for (const hil::UnitEntry& entry : station.units) {
    const auto want = expected.find(entry.role);
    if (want == expected.end()) {
      check.station.units.push_back(entry);
      continue;
    }
    if (!clock) clock = hil::MakeClock(station.time_scale, station.clock_file);
    hil::UnitLink link(entry, *clock);
    const std::string serial = hil::UnitSerialText(entry.kind, link.Identify().serial_number);
    if (serial == want->second) {
      check.station.units.push_back(entry);
    } else {
      check.refused.push_back(fmt::format(
          "{} (slot {}, {}): the unit says it is {}, the campaign file expects {}: this slot "
          "is left out of the campaign, nothing was run on it",
          entry.role,
          entry.slot,
          entry.port.path,
          serial,
          want->second));
    }
  }
  return check;
}

std::string WriteCheckedStation(const hil::Station& station,
                                const std::filesystem::path& dir,
                                const std::filesystem::path& original) {
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / original.filename();
  common::WriteFileAtomically(path, station.ToJson().dump(2) + "\n");
  return path.string();
}

void RequireExpectedRolesExist(const std::map<std::string, std::string>& expected,
                               const std::string& imu_station_file,
                               const std::string& ads_station_file) {
  std::set<std::string> roles;
  for (const std::string& file : {imu_station_file, ads_station_file}) {
    if (file.empty()) continue;
    for (const hil::UnitEntry& u : hil::Station::Load(file).units) roles.insert(u.role);
  }
  for (const auto& [role, serial] : expected) {
    if (roles.count(role) == 0) {
      throw common::ParamError(fmt::format(
          "expected_serials.{}: no station given has a unit role {} (serial {} expected)",
          role,
          role,
          serial));
    }
  }
}

}  // namespace adahrs::calib
