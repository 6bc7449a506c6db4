#include "hil/drivers/station_instruments.h"

#include <iostream>

#include "hil/drivers/console_operator.h"
#include "hil/drivers/virtual_fixture_operator.h"

namespace adahrs::hil {

StationInstruments OpenStation(const Station& station, const Clock& clock) {
  StationInstruments out;
  if (station.op.type == OperatorType::kVirtualFixture) {
    out.op = std::make_unique<VirtualFixtureOperator>(station.op, clock, std::clog);
  } else {
    out.op = std::make_unique<ConsoleOperator>(std::cin, std::cout);
  }
  for (const UnitEntry& unit : station.units) {
    out.units.push_back(std::make_unique<UnitLink>(unit, clock));
  }
  return out;
}

}  // namespace adahrs::hil
