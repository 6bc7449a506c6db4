#include "hil/drivers/port_check.h"

#include <memory>
#include <sstream>

#include <fmt/format.h>

#include "hil/drivers/adts_prologix.h"
#include "hil/drivers/atl_rate_table.h"
#include "hil/drivers/unit_link.h"
#include "hil/drivers/unit_serial.h"
#include "hil/drivers/virtual_fixture_operator.h"
#include "hil/drivers/watlow942_chamber.h"
#include "hil/drivers/watlow_f4_chamber.h"

namespace adahrs::hil {
namespace {

InstrumentIdentity IdentifyInstrument(const InstrumentEntry& e, const Clock& clock) {
  switch (e.type) {
    case InstrumentType::kAerosmithAtl:
      return AtlRateTable(e, clock).Identify();
    case InstrumentType::kWatlowF4:
      return WatlowF4Chamber(e, clock).Identify();
    case InstrumentType::kWatlow942:
      return Watlow942Chamber(e, clock).Identify();
    case InstrumentType::kDruckAdtsPrologix:
      return AdtsPrologix(e, clock).Identify();
  }
  return {};
}

std::string UnitIdentity(const UnitEntry& u, const Clock& clock) {
  UnitLink link(u, clock);
  const hil::IdentifyInfo info = link.Identify();
  return fmt::format(
      "{} firmware {}.{}.{} mode {} constants {}",
      UnitSerialText(u.kind, info.serial_number),
      info.firmware_major,
      info.firmware_minor,
      info.firmware_patch,
      info.mode,
      info.constants_valid ? fmt::format("v{}", info.constants_version) : std::string("none"));
}

template <typename Check>
PortCheckRow Row(const std::string& role, const std::string& port, Check check) {
  PortCheckRow row{role, port, "", false, ""};
  try {
    row.identity = check();
    row.ok = true;
    row.status = "ok";
  } catch (const std::exception& e) {
    row.status = e.what();
  }
  return row;
}

}  // namespace

std::vector<PortCheckRow> CheckPorts(const Station& station, const Clock& clock) {
  std::vector<PortCheckRow> rows;
  for (const InstrumentEntry& e : station.instruments) {
    rows.push_back(Row(e.role, e.port.path, [&] {
      const InstrumentIdentity id = IdentifyInstrument(e, clock);
      return id.model + ": " + id.detail;
    }));
  }
  for (const UnitEntry& u : station.units) {
    rows.push_back(Row(u.role, u.port.path, [&] { return UnitIdentity(u, clock); }));
  }
  if (station.op.type == OperatorType::kVirtualFixture) {
    rows.push_back(Row("operator", station.op.port.path, [&] {
      std::ostringstream log;
      VirtualFixtureOperator op(station.op, clock, log);
      return std::string("virtual fixture (port opened)");
    }));
  } else {
    rows.push_back(PortCheckRow{"operator", "console", "console", true, "ok"});
  }
  return rows;
}

}  // namespace adahrs::hil
